#include <memory>
#include <vector>

#include "harbour/machines/tractor/TerminalTractor.h"
#include "harbour/machines/tractor/TractorAutopilot.h"
#include "harbour/sim/MachineType.h"

namespace harbour::sim {
namespace {
constexpr PilotType kPilots[] = {pilot_type<TractorAutopilot>()};
constexpr std::string_view kDeductions[] = {"jackknife", "speeding"};  // and every machine's
constexpr std::string_view kFigures[] = {"container_collisions", "vehicle_collisions", "travel_energy_j",
                                         "jackknifes",           "overspeeds",         "worst_overspeed_kmh"};
}  // namespace

const MachineType& tractor_machine_type() {
  static constexpr MachineType type{
      "tractor", "ro-ro terminal tractor", Handles::kTrailer, {}, false, kPilots, kDeductions, kFigures};
  return type;
}

std::unique_ptr<Machine> TractorSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<TerminalTractor>(world, vehicle, start);
}

}  // namespace harbour::sim
