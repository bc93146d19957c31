#pragma once

#include <vector>

#include "harbour/cable/CableBodies.h"
#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// The cable model's bodies as ODE bodies: reeving body i is `bodies[i]` of the physics world, its mounts
/// given from `origins[i]` in that body's frame (where the reeving file's frame of the body sits: a boom's
/// head, a house's slewing ring; none: the body's centre).
class OdeCableBodies : public cable::CableBodies {
 public:
  OdeCableBodies(physics::PhysicsWorld& world, std::vector<physics::BodyId> bodies,
                 std::vector<core::Vec3> origins = {})
      : world_(world), bodies_(std::move(bodies)), origins_(std::move(origins)) {
    if (!origins_.empty()) origins_.resize(bodies_.size());
  }

  core::Vec3 point_position(int body, const core::Vec3& local) const override {
    return world_.point_position(map(body), at(body, local));
  }
  core::Vec3 point_velocity(int body, const core::Vec3& local) const override {
    return world_.point_velocity(map(body), at(body, local));
  }
  core::Vec3 angular_velocity(int body) const override { return world_.angular_velocity(map(body)); }
  void add_force(int body, const core::Vec3& world_point, const core::Vec3& force) override {
    world_.add_force_at(map(body), world_point, force);
  }

 private:
  physics::BodyId map(int body) const {
    return body < 0 ? physics::kWorld : bodies_[static_cast<std::size_t>(body)];
  }
  core::Vec3 at(int body, const core::Vec3& local) const {
    return body < 0 || origins_.empty() ? local : origins_[static_cast<std::size_t>(body)] + local;
  }
  physics::PhysicsWorld& world_;
  std::vector<physics::BodyId> bodies_;
  std::vector<core::Vec3> origins_;
};

}  // namespace harbour::sim
