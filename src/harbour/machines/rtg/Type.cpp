#include <memory>
#include <vector>

#include "harbour/machines/MachineType.h"
#include "harbour/machines/rtg/RubberTyredGantry.h"
#include "harbour/sim/Autopilot.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kHoistBrake, MachineFault::kLandedSensor};
constexpr PilotType kPilots[] = {pilot_type<Autopilot>()};
}  // namespace

const MachineType& rtg_machine_type() {
  static constexpr MachineType type{"rtg",  "rubber-tyred gantry crane", Handles::kContainers, kFaults, true,
                                    kPilots};
  return type;
}

std::unique_ptr<Machine> RtgSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<RubberTyredGantry>(world, crane, start);
}

}  // namespace harbour::sim
