#include "harbour/machines/Machine.h"
#include "harbour/machines/MachineType.h"
#include "harbour/sim/TractorAutopilot.h"

namespace harbour::sim {
namespace {
constexpr PilotType kPilots[] = {pilot_type<TractorAutopilot>()};
}  // namespace

const MachineType& tractor_machine_type() {
  static constexpr MachineType type{"tractor", "ro-ro terminal tractor", Handles::kTrailer, {}, false,
                                    kPilots};
  return type;
}

}  // namespace harbour::sim
