#include "harbour/machines/GantryCrane.h"

#include "harbour/machines/parts/KineticDamping.h"
#include "harbour/sim/Machine.h"

namespace harbour::sim {

void settle_gantry_crane(Machine& crane, physics::PhysicsWorld& world,
                         std::span<const physics::BodyId> bodies, SpreaderHoist& rig) {
  constexpr int kSteps = 3000;
  constexpr double kDt = 0.001;
  const scene::Controls neutral = crane.control_table().neutral();
  settle_by_kinetic_damping(
      world, bodies, kSteps,
      [&] {
        crane.step(neutral, {}, kDt);
        world.step(kDt);
      },
      [&] { rig.hoist().stop_transverse_motion(); });
  static_cast<void>(rig.hoist().take_events());  // the settling's rope events are not the exercise's
}

}  // namespace harbour::sim
