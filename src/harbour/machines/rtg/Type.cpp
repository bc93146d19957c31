#include <memory>
#include <vector>

#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/rtg/RubberTyredGantry.h"
#include "harbour/sim/MachineType.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kHoistBrake, MachineFault::kLandedSensor};
constexpr PilotType kPilots[] = {pilot_type<GantryAutopilot>()};
constexpr std::string_view kDeductions[] = {"hard_landing",     "landing_while_swaying",
                                            "twistlock_misuse", "rope_overload",
                                            "limit_switch_hit", "gantry_travel_without_horn",
                                            "load_drop",        "lift_under_fault"};  // and every machine's
constexpr std::string_view kFigures[] = {
    "container_collisions",   "vehicle_collisions", "hard_landings",  "worst_landing_mps",
    "sway_landings",          "twistlock_misuse",   "overloads",      "limit_hits",
    "unwarned_gantry_travel", "load_drops",         "hoist_energy_j", "travel_energy_j"};
}  // namespace

const MachineType& rtg_machine_type() {
  static constexpr MachineType type{
      "rtg",   "rubber-tyred gantry crane", Handles::kContainers, kFaults, true, kPilots, kDeductions,
      kFigures};
  return type;
}

std::unique_ptr<Machine> RtgSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<RubberTyredGantry>(world, crane, start);
}

}  // namespace harbour::sim
