#include <memory>
#include <vector>

#include "harbour/machines/reach_stacker/ReachStacker.h"
#include "harbour/machines/reach_stacker/ReachStackerAutopilot.h"
#include "harbour/sim/MachineType.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kLoadMomentLimiter, MachineFault::kLandedSensor};
constexpr PilotType kPilots[] = {pilot_type<ReachStackerAutopilot>()};
constexpr std::string_view kDeductions[] = {
    "hard_landing", "landing_while_swaying", "twistlock_misuse", "limiter_trip", "tip_over", "speeding",
    "load_drop"};  // and every machine's
constexpr std::string_view kFigures[] = {
    "container_collisions", "vehicle_collisions", "hard_landings", "worst_landing_mps",
    "sway_landings",        "twistlock_misuse",   "load_drops",    "travel_energy_j",
    "limiter_trips",        "tip_overs",          "overspeeds",    "worst_overspeed_kmh"};
}  // namespace

const MachineType& reach_stacker_machine_type() {
  static constexpr MachineType type{
      "reach_stacker", "reach stacker", Handles::kContainers, kFaults, true, kPilots, kDeductions, kFigures};
  return type;
}

std::unique_ptr<Machine> ReachStackerSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<ReachStacker>(world, vehicle, start);
}

}  // namespace harbour::sim
