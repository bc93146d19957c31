#pragma once

#include "harbour/core/Vec3.h"

namespace harbour::cable {

/// The small interface through which the cable model reads the bodies that carry its elements and pushes on
/// them. The physics layer implements it over ODE bodies; tests implement it over point masses.
class CableBodies {
 public:
  virtual ~CableBodies() = default;
  /// World position of a point given in body `body`'s frame.
  virtual core::Vec3 point_position(int body, const core::Vec3& local) const = 0;
  /// World velocity of that point.
  virtual core::Vec3 point_velocity(int body, const core::Vec3& local) const = 0;
  /// Angular velocity of body `body` in the world frame (zero for the world and for bodies that do not turn).
  virtual core::Vec3 angular_velocity(int body) const {
    (void)body;
    return {};
  }
  /// Adds a world force at a world point for the next physics step.
  virtual void add_force(int body, const core::Vec3& world_point, const core::Vec3& force) = 0;
};

}  // namespace harbour::cable
