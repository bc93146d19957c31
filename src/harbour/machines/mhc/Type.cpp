#include "harbour/machines/Machine.h"
#include "harbour/machines/MachineType.h"
#include "harbour/sim/GrabAutopilot.h"
#include "harbour/sim/HookAutopilot.h"

namespace harbour::sim {
namespace {
constexpr MachineFault kFaults[] = {MachineFault::kHoistBrake};
constexpr PilotType kPilots[] = {pilot_type<GrabAutopilot>(), pilot_type<HookAutopilot>()};
}  // namespace

const MachineType& mhc_machine_type() {
  static constexpr MachineType type{"mhc",  "mobile harbour crane", Handles::kBulkOrCargo, kFaults, false,
                                    kPilots};
  return type;
}

}  // namespace harbour::sim
