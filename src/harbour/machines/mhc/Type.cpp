#include <memory>
#include <vector>

#include "harbour/machines/mhc/GrabAutopilot.h"
#include "harbour/machines/mhc/HookAutopilot.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/sim/MachineType.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kHoistBrake, MachineFault::kLoadMomentLimiter};
constexpr PilotType kPilots[] = {pilot_type<GrabAutopilot>(), pilot_type<HookAutopilot>()};
constexpr std::string_view kDeductions[] = {
    "hard_landing", "landing_while_swaying", "rope_overload", "limit_switch_hit",
    "load_drop",    "lift_under_fault",      "tonne_spilled", "tonne_short",
    "poor_bite",    "limiter_trip",          "pad_lift_off",  "decimetre_above_trim"};  // and every machine's
constexpr std::string_view kFigures[] = {
    "container_collisions", "ship_collisions", "vehicle_collisions", "hard_landings",
    "worst_landing_mps",    "sway_landings",   "overloads",          "limit_hits",
    "load_drops",           "hoist_energy_j",  "limiter_trips",      "pad_lift_offs"};
}  // namespace

const MachineType& mhc_machine_type() {
  static constexpr MachineType type{
      "mhc", "mobile harbour crane", Handles::kBulkOrCargo, kFaults, false, kPilots, kDeductions, kFigures};
  return type;
}

std::unique_ptr<Machine> MhcSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<MobileHarbourCrane>(world, crane, start);
}

std::vector<cable::ReevingSettings*> MhcSetup::reevings() {
  std::vector<cable::ReevingSettings*> all{&crane.luffing, &crane.hoist};
  if (crane.hook) all.push_back(&crane.hook->hoist);
  return all;
}

}  // namespace harbour::sim
