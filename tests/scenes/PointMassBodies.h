#pragma once

// Test double for cable::CableBodies: point masses (no rotation) integrated by semi-implicit Euler under
// gravity, with an optional floor. Shared by the cable tests and benchmark.

#include <algorithm>
#include <vector>

#include "harbour/cable/CableBodies.h"

namespace harbour::scenes {

class PointMassBodies : public cable::CableBodies {
 public:
  struct Body {
    core::Vec3 position, velocity, force;
    double mass_kg = 1.0;
    bool fixed = false;
    double floor_z = -1e30;  ///< [m] the body rests on a floor at this height
  };

  int add(const core::Vec3& position, double mass_kg, bool fixed = false) {
    bodies.push_back({position, {}, {}, mass_kg, fixed});
    return static_cast<int>(bodies.size()) - 1;
  }

  core::Vec3 point_position(int body, const core::Vec3& local) const override {
    return body < 0 ? local : bodies[body].position + local;
  }
  core::Vec3 point_velocity(int body, const core::Vec3&) const override {
    return body < 0 ? core::Vec3{} : bodies[body].velocity;
  }
  void add_force(int body, const core::Vec3&, const core::Vec3& force) override {
    bodies[body].force += force;
  }

  /// Integrates every free body over `dt` and clears the forces.
  void step(double dt, const core::Vec3& gravity) {
    for (Body& b : bodies) {
      if (!b.fixed) {
        b.velocity += (gravity + b.force * (1.0 / b.mass_kg)) * dt;
        b.position += b.velocity * dt;
        if (b.position.z < b.floor_z) {
          b.position.z = b.floor_z;
          b.velocity = {};
        }
      }
      last_force = b.force;
      b.force = {};
    }
  }

  std::vector<Body> bodies;
  core::Vec3 last_force;  ///< force on the last body before clearing (for slack checks)
};

}  // namespace harbour::scenes
