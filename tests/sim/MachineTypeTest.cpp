// The machine registry: one type per machine folder, generated from the folders; each type says what its
// machine is without building one, and what it says is what the built machine does.
#include "harbour/machines/MachineType.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Pilot.h"
#include "harbour/sim/Simulation.h"

namespace harbour::sim {
namespace {

TEST(MachineTypes, EveryMachineFolderWithATypeIsRegisteredByItsName) {
  std::set<std::string> folders, registered;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/../src/harbour/machines"))
    if (std::filesystem::exists(entry.path() / "Type.cpp")) folders.insert(entry.path().filename().string());
  for (const MachineType* type : machine_types()) {
    registered.insert(type->kind);
    EXPECT_EQ(find_machine_type(type->kind), type);
    EXPECT_FALSE(type->pilots.empty()) << type->kind << " has no scripted operator";
  }
  EXPECT_EQ(folders, registered);
  EXPECT_GE(registered.size(), 5u);
  EXPECT_EQ(find_machine_type("crane"), nullptr);
}

// Built from each shipped exercise, a machine is of its type: the faults the type lists are the ones the
// machine takes (its fault lamp lights), the others are refused before anything changes; and one of the
// type's scripted operators drives at least one of its exercises.
TEST(MachineTypes, WhatATypeSaysIsWhatItsMachineDoes) {
  using Kind = InstructorCommand::Kind;
  const std::map<Kind, MachineFault> faults = {{Kind::kHoistBrakeFault, MachineFault::kHoistBrake},
                                               {Kind::kLandedSensorFault, MachineFault::kLandedSensor},
                                               {Kind::kLimiterFault, MachineFault::kLoadMomentLimiter}};
  std::set<std::string> checked, driven;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/exercises")) {
    const ExerciseSettings exercise = io::load_exercise(entry.path().string());
    const std::string kind = machine_kind(exercise.scenario.machine);
    if (why_no_pilot(exercise).empty()) driven.insert(kind);
    if (!checked.insert(kind).second) continue;
    Simulation sim(exercise.scenario);
    const MachineType& type = sim.machine().type();
    ASSERT_EQ(&type, find_machine_type(kind)) << entry.path();
    for (const auto& [command_kind, fault] : faults) {
      InstructorCommand command;
      command.kind = command_kind;
      if (type.has_fault(fault)) {
        EXPECT_EQ(sim.why_refused(command), "") << kind;
        sim.command(command);
        sim.step(sim.control_table().neutral());
        EXPECT_TRUE(sim.machine().fault_active(fault)) << kind << " fault " << static_cast<int>(fault);
      } else {
        EXPECT_NE(sim.why_refused(command), "") << kind << " fault " << static_cast<int>(fault);
        EXPECT_FALSE(sim.machine().fault_active(fault)) << kind;
      }
    }
  }
  EXPECT_EQ(checked.size(), machine_types().size());
  EXPECT_EQ(driven, checked);
}

// An exercise may script only the faults its machine has the parts for: the loader names the ones it has.
TEST(MachineTypes, EachTypeOffersTheEventsOfItsParts) {
  EXPECT_EQ(io::event_kinds(*find_machine_type("sts")),
            (std::vector<std::string>{"gust", "hoist_brake_fault", "landed_sensor_fault"}));
  EXPECT_EQ(io::event_kinds(*find_machine_type("mhc")),
            (std::vector<std::string>{"gust", "hoist_brake_fault"}));
  EXPECT_EQ(io::event_kinds(*find_machine_type("tractor")), (std::vector<std::string>{"gust"}));
  EXPECT_EQ(io::event_kinds(*find_machine_type("reach_stacker")),
            (std::vector<std::string>{"gust", "landed_sensor_fault", "limiter_fault"}));
}

}  // namespace
}  // namespace harbour::sim
