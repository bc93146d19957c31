#include "harbour/machines/Machine.h"
#include "harbour/machines/MachineType.h"
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

}  // namespace harbour::sim
