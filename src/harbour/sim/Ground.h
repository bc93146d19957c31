#pragma once

#include "harbour/core/Vec3.h"

namespace harbour::sim {

/// The ground under a point of the site, locally a plane: its height, its upward unit normal, how fast it
/// rises (a vessel's deck in a swell) and its grip (a tyre's friction scales by it: a wet steel ramp less
/// than the quay's 1).
struct GroundContact {
  double z_m = 0.0;
  core::Vec3 normal{0.0, 0.0, 1.0};
  double rise_mps = 0.0;
  double grip = 1.0;
};

/// What wheels stand on (the world's: a quay, a ramp, a vessel's deck).
class Ground {
 public:
  virtual ~Ground() = default;
  virtual GroundContact at(double x_m, double y_m) const = 0;
};

/// A level ground at one height.
class FlatGround final : public Ground {
 public:
  explicit FlatGround(double z_m = 0.0) : z_m_(z_m) {}
  GroundContact at(double, double) const override { return {z_m_, {0.0, 0.0, 1.0}, 0.0, 1.0}; }

 private:
  double z_m_;
};

}  // namespace harbour::sim
