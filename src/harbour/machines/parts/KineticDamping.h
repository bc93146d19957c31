#pragma once

#include <span>

#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// Dynamic relaxation with kinetic damping: brings a machine to rest in its static equilibrium before an
/// exercise starts (ropes stretched under their loads, joints deflected under theirs, loads plumb under their
/// suspension). `advance` steps the machine at rest through `steps` steps of the world; each time the bodies'
/// kinetic energy passes a peak they are all stopped, and `stop_rest` stops whatever else moves with them
/// (the ropes' waves). Each stop takes out the energy of the modes then swinging, so their bounces die in a
/// few periods instead of ringing on into the exercise.
template <class Advance, class StopRest>
void settle_by_kinetic_damping(physics::PhysicsWorld& world, std::span<const physics::BodyId> bodies,
                               int steps, Advance advance, StopRest stop_rest) {
  double last_energy = 0.0;
  for (int k = 0; k < steps; ++k) {
    advance();
    double energy = 0.0;
    for (const physics::BodyId b : bodies) {
      const core::Vec3 v = world.linear_velocity(b), w = world.angular_velocity(b);
      energy += world.mass_kg(b) * dot(v, v) + dot(w, w) * world.mass_kg(b);  // a measure, not joules
    }
    if (energy < last_energy) {
      for (const physics::BodyId b : bodies)
        world.stop_body(b);
      stop_rest();
      energy = 0.0;
    }
    last_energy = energy;
  }
}

}  // namespace harbour::sim
