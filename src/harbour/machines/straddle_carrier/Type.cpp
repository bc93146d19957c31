#include <memory>
#include <vector>

#include "harbour/machines/straddle_carrier/StraddleCarrier.h"
#include "harbour/machines/straddle_carrier/StraddleCarrierAutopilot.h"
#include "harbour/sim/MachineType.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kHoistBrake, MachineFault::kLandedSensor};
constexpr PilotType kPilots[] = {pilot_type<StraddleCarrierAutopilot>()};
constexpr std::string_view kDeductions[] = {"hard_landing",  "landing_while_swaying", "twistlock_misuse",
                                            "rope_overload", "limit_switch_hit",      "speeding",
                                            "load_drop",     "lift_under_fault"};  // and every machine's
constexpr std::string_view kFigures[] = {
    "container_collisions", "vehicle_collisions", "hard_landings",      "worst_landing_mps", "sway_landings",
    "twistlock_misuse",     "overloads",          "limit_hits",         "load_drops",        "hoist_energy_j",
    "travel_energy_j",      "overspeeds",         "worst_overspeed_kmh"};
}  // namespace

const MachineType& straddle_carrier_machine_type() {
  static constexpr MachineType type{"straddle_carrier",
                                    "straddle carrier",
                                    Handles::kContainers,
                                    kFaults,
                                    false,
                                    kPilots,
                                    kDeductions,
                                    kFigures};
  return type;
}

std::unique_ptr<Machine> StraddleCarrierSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<StraddleCarrier>(world, vehicle, start);
}

}  // namespace harbour::sim
