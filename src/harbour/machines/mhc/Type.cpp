#include <memory>
#include <vector>

#include "harbour/machines/MachineType.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
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

std::unique_ptr<Machine> MhcSetup::build(physics::PhysicsWorld& world) const {
  return std::make_unique<MobileHarbourCrane>(world, crane, start);
}

std::vector<cable::ReevingSettings*> MhcSetup::reevings() {
  std::vector<cable::ReevingSettings*> all{&crane.luffing, &crane.hoist};
  if (crane.hook) all.push_back(&crane.hook->hoist);
  return all;
}

}  // namespace harbour::sim
