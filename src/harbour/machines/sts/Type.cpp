#include <memory>
#include <vector>

#include "harbour/machines/MachineType.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/sim/Autopilot.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kHoistBrake, MachineFault::kLandedSensor};
constexpr PilotType kPilots[] = {pilot_type<Autopilot>()};
}  // namespace

const MachineType& sts_machine_type() {
  static constexpr MachineType type{"sts",  "ship-to-shore gantry crane", Handles::kContainers, kFaults, true,
                                    kPilots};
  return type;
}

std::unique_ptr<Machine> StsSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<StsCrane>(world, crane, gantry_y_m, trolley_x_m, spreader_z_m);
}

}  // namespace harbour::sim
