#include <memory>
#include <vector>

#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/sts/StsCrane.h"
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
    "container_collisions", "cell_guide_collisions",  "ship_collisions",
    "vehicle_collisions",   "hard_landings",          "worst_landing_mps",
    "sway_landings",        "twistlock_misuse",       "overloads",
    "limit_hits",           "unwarned_gantry_travel", "load_drops",
    "hoist_energy_j",       "travel_energy_j"};
}  // namespace

const MachineType& sts_machine_type() {
  static constexpr MachineType type{
      "sts",   "ship-to-shore gantry crane", Handles::kContainers, kFaults, true, kPilots, kDeductions,
      kFigures};
  return type;
}

std::unique_ptr<Machine> StsSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<StsCrane>(world, crane, gantry_y_m, trolley_x_m, spreader_z_m);
}

}  // namespace harbour::sim
