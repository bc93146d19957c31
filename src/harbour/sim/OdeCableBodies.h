#pragma once

#include <vector>

#include "harbour/cable/CableBodies.h"
#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// The cable model's bodies as ODE bodies: reeving body i is `bodies[i]` of the physics world.
class OdeCableBodies : public cable::CableBodies {
 public:
  OdeCableBodies(physics::PhysicsWorld& world, std::vector<physics::BodyId> bodies)
      : world_(world), bodies_(std::move(bodies)) {}

  core::Vec3 point_position(int body, const core::Vec3& local) const override {
    return world_.point_position(map(body), local);
  }
  core::Vec3 point_velocity(int body, const core::Vec3& local) const override {
    return world_.point_velocity(map(body), local);
  }
  void add_force(int body, const core::Vec3& world_point, const core::Vec3& force) override {
    world_.add_force_at(map(body), world_point, force);
  }

 private:
  physics::BodyId map(int body) const {
    return body < 0 ? physics::kWorld : bodies_[static_cast<std::size_t>(body)];
  }
  physics::PhysicsWorld& world_;
  std::vector<physics::BodyId> bodies_;
};

}  // namespace harbour::sim
