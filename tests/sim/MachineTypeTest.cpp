// The machine registry: one type per machine folder, generated from the folders; each type says what its
// machine is without building one, and what it says is what the built machine does.
#include "harbour/machines/MachineRegistry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/machines/reach_stacker/ReachStacker.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"
#include "harbour/sim/Simulation.h"
#include "harbour/training/Figures.h"

namespace harbour::sim {
namespace {

constexpr MachineType kNoFigures{};

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

// Each machine folder brings the reader of its machine file and its exercises' start block, registered by
// the same name as its type; every kind a machine file can declare has one.
TEST(MachineTypes, EveryTypeHasTheReaderOfItsFilesFromItsFolder) {
  std::set<std::string> folders, readers, types;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/../src/harbour/machines"))
    if (std::filesystem::exists(entry.path() / "Files.cpp")) folders.insert(entry.path().filename().string());
  for (const io::MachineFileType* files : io::machine_file_types()) {
    readers.insert(files->kind);
    EXPECT_EQ(io::find_machine_file_type(files->kind), files);
    EXPECT_TRUE(files->read && files->start_pose_form) << files->kind;
    const std::string section = files->start_section;
    EXPECT_TRUE(section == "crane" || section == "vehicle") << files->kind << ": " << section;
  }
  for (const MachineType* type : machine_types())
    types.insert(type->kind);
  EXPECT_EQ(folders, readers);
  EXPECT_EQ(readers, types);
  EXPECT_EQ(io::find_machine_file_type("crane"), nullptr);
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
    const std::string kind = exercise.scenario.machine.kind();
    if (why_no_pilot(exercise).empty()) driven.insert(kind);
    if (!checked.insert(kind).second) continue;
    Simulation sim(exercise.scenario);
    const MachineType& type = sim.machine().type();
    ASSERT_EQ(&type, find_machine_type(kind)) << entry.path();
    ASSERT_EQ(&exercise.scenario.machine.type(), &type);
    EXPECT_FALSE(io::start_pose_form(exercise.scenario.machine).fields.empty()) << kind;
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
            (std::vector<std::string>{"gust", "hoist_brake_fault", "limiter_fault"}));
  EXPECT_EQ(io::event_kinds(*find_machine_type("tractor")), (std::vector<std::string>{"gust"}));
  EXPECT_EQ(io::event_kinds(*find_machine_type("reach_stacker")),
            (std::vector<std::string>{"gust", "landed_sensor_fault", "limiter_fault"}));
}

// the first shipped exercise of a machine of this kind (by file name)
ExerciseSettings first_exercise_of(std::string_view kind) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/exercises"))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const std::filesystem::path& file : files)
    if (ExerciseSettings exercise = io::load_exercise(file.string());
        exercise.scenario.machine.kind() == kind)
      return exercise;
  throw std::runtime_error("no shipped exercise of " + std::string(kind));
}

// The console's panel offers an instructor the faults of the selected station's machine, by the commands'
// names: each one the station takes (InstructorCommandText), none of a part the machine lacks.
TEST(MachineTypes, AnInstructorIsOfferedTheFaultsOfTheMachinesParts) {
  EXPECT_EQ(io::instructor_faults(*find_machine_type("sts")),
            (std::vector<std::string>{"hoist-brake-fault", "landed-sensor-fault"}));
  EXPECT_EQ(io::instructor_faults(*find_machine_type("reach_stacker")),
            (std::vector<std::string>{"landed-sensor-fault", "limiter-fault"}));
  EXPECT_TRUE(io::instructor_faults(*find_machine_type("tractor")).empty());
  for (const MachineType* type : machine_types()) {
    const Simulation simulation(first_exercise_of(type->kind).scenario);
    std::size_t offered = 0;
    for (const std::string& fault : io::instructor_faults(*type)) {
      const std::string command = "0:" + fault + (fault == "landed-sensor-fault" ? ":2" : "");
      const io::TimedCommand parsed = io::parse_instructor_command(command);
      EXPECT_EQ(simulation.why_refused(parsed.command), "") << type->kind << " " << fault;
      ++offered;
    }
    EXPECT_EQ(offered, type->faults.size()) << type->kind;
  }
}

// The deductions a type lists are the rubric's, each of the rubric's is some machine's, and a machine is
// not offered what it has no part for (the designer's rubric shows a type's list only).
TEST(MachineTypes, EachTypeListsTheDeductionsItsOperatorCanIncur) {
  std::set<std::string> rubric, incurred;
  for (const io::RuleField& f : io::rule_deductions())
    rubric.insert(f.key);
  for (const std::string_view d : kEveryMachinesDeductions) {
    EXPECT_TRUE(rubric.count(std::string(d))) << "every machine's '" << d << "' is not a rubric key";
    incurred.insert(std::string(d));
  }
  for (const MachineType* type : machine_types()) {
    for (const std::string_view d : type->deductions) {
      EXPECT_TRUE(rubric.count(std::string(d))) << type->kind << " lists '" << d << "', not a rubric key";
      EXPECT_FALSE(std::count(std::begin(kEveryMachinesDeductions), std::end(kEveryMachinesDeductions), d))
          << type->kind << " lists every machine's '" << d << "' again";
      incurred.insert(std::string(d));
    }
    EXPECT_TRUE(type->can_incur("collision") && type->can_incur("late_stop_signal")) << type->kind;
  }
  EXPECT_EQ(incurred, rubric);
  const MachineType& sts = *find_machine_type("sts");
  EXPECT_FALSE(sts.can_incur("jackknife"));
  EXPECT_FALSE(sts.can_incur("pad_lift_off"));
  EXPECT_TRUE(sts.can_incur("gantry_travel_without_horn"));
  EXPECT_FALSE(find_machine_type("tractor")->can_incur("twistlock_misuse"));
  EXPECT_TRUE(find_machine_type("mhc")->can_incur("pad_lift_off"));
}

// every figure a machine's parts can measure: a Metrics with no machine type stores them all (a vehicle's
// too)
std::set<std::string> part_figures() {
  Metrics every;
  every.vehicle = true;
  Metrics common;
  common.machine = &kNoFigures;
  std::set<std::string> names;
  for (const auto& [name, value] : every.rows())
    names.insert(name);
  for (const auto& [name, value] : common.rows())
    names.erase(name);
  return names;
}

TEST(MachineTypes, ItsFiguresAreFiguresItsPartsMeasureAndTheRecordsKnow) {
  const std::set<std::string> parts = part_figures();
  EXPECT_EQ(parts.size(), 20u);
  for (const MachineType* type : machine_types()) {
    EXPECT_GT(type->figures.size(), 0u) << type->kind;
    for (const std::string_view figure : type->figures) {
      EXPECT_TRUE(parts.contains(std::string(figure))) << type->kind << ": " << figure;
      EXPECT_LT(training::figure_order(std::string(figure)), training::figure_table().size())
          << type->kind << ": " << figure << " has no words in the reports";
    }
  }
}

TEST(MachineTypes, WhatItsRubricDeductsItsAttemptsStore) {
  // a deduction its operator can incur and the figure that counts it: an attempt's record shows what cost
  // points
  const std::map<std::string_view, std::string_view> counted_by = {
      {"hard_landing", "hard_landings"},
      {"landing_while_swaying", "sway_landings"},
      {"twistlock_misuse", "twistlock_misuse"},
      {"rope_overload", "overloads"},
      {"limit_switch_hit", "limit_hits"},
      {"gantry_travel_without_horn", "unwarned_gantry_travel"},
      {"load_drop", "load_drops"},
      {"limiter_trip", "limiter_trips"},
      {"pad_lift_off", "pad_lift_offs"},
      {"tip_over", "tip_overs"},
      {"jackknife", "jackknifes"},
      {"speeding", "overspeeds"}};
  for (const MachineType* type : machine_types())
    for (const auto& [deduction, figure] : counted_by) {
      if (type->can_incur(deduction)) {
        EXPECT_TRUE(type->measures(figure))
            << type->kind << " deducts " << deduction << " but stores no " << figure;
      }
    }
}

TEST(MachineTypes, EachMachinesAttemptStoresItsOwnFiguresAndNoOthers) {
  const std::set<std::string> parts = part_figures();
  for (const MachineType* type : machine_types()) {
    const ExerciseSettings exercise = first_exercise_of(type->kind);
    Simulation simulation(exercise.scenario);
    Evaluator evaluator(exercise);
    const scene::Controls neutral = simulation.control_table().neutral();
    simulation.step(neutral);
    evaluator.observe(simulation, neutral);
    std::set<std::string> stored;
    for (const auto& [name, value] : evaluator.metrics().rows())
      if (parts.contains(name)) stored.insert(name);
    EXPECT_EQ(stored, std::set<std::string>(type->figures.begin(), type->figures.end())) << exercise.name;
  }
  // what the tractor has no part for is not stored as a zero; what the reach stacker has, is
  const MachineType& tractor = *find_machine_type("tractor");
  for (const char* none : {"twistlock_misuse", "hoist_energy_j", "unwarned_gantry_travel", "hard_landings"})
    EXPECT_FALSE(tractor.measures(none)) << none;
  const MachineType& stacker = *find_machine_type("reach_stacker");
  for (const char* figure : {"limiter_trips", "tip_overs", "twistlock_misuse"})
    EXPECT_TRUE(stacker.measures(figure)) << figure;
}

// A scenario's machine is a value: a copy changed leaves the original as it was; asked for another
// machine's setup it says which it is.
TEST(MachineSetup, IsAValueOfOneKind) {
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_hook_lift.yaml");
  ScenarioSettings copy = exercise.scenario;
  const double boom_rad = exercise.scenario.machine.as<MhcSetup>().start.boom_rad;
  copy.machine.as<MhcSetup>().start.boom_rad = boom_rad + 0.1;
  EXPECT_EQ(exercise.scenario.machine.as<MhcSetup>().start.boom_rad, boom_rad);
  EXPECT_EQ(copy.machine.as<MhcSetup>().start.boom_rad, boom_rad + 0.1);
  EXPECT_EQ(copy.machine.get_if<StsSetup>(), nullptr);
  try {
    (void)copy.machine.as<StsSetup>();
    ADD_FAILURE() << "an MHC read as an STS";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "the machine is an mhc, not an sts");
  }
  EXPECT_EQ(copy.machine.reevings().size(), 3u);  // luffing, grab, hook
  // no machine of its own: a scenario is given one by its exercise, and builds nothing without it
  const ScenarioSettings bare;
  EXPECT_FALSE(bare.machine.has_value());
  EXPECT_THROW((void)bare.machine.kind(), std::logic_error);
  EXPECT_THROW(Simulation{bare}, std::logic_error);
}

TEST(MachineSetup, AReachStackersEndStopsGoToItsTravelOnlyWhereAnOldRunAsks) {
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/reach_stacker_stack.yaml");
  MachineSetup as_recorded = exercise.scenario.machine;
  as_recorded.end_stops_at_travel();
  EXPECT_GT(exercise.scenario.machine.as<ReachStackerSetup>().vehicle.telescope_end_stop_margin_m, 0.0);
  EXPECT_EQ(as_recorded.as<ReachStackerSetup>().vehicle.telescope_end_stop_margin_m, 0.0);
  MachineSetup sts = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml").scenario.machine;
  sts.end_stops_at_travel();  // it has no such margin: nothing changes, nothing throws
  EXPECT_STREQ(sts.kind(), "sts");
}

}  // namespace
}  // namespace harbour::sim
