#pragma once

#include <algorithm>
#include <cstdint>

#include "harbour/core/Braking.h"
#include "harbour/core/StateArchive.h"

namespace harbour::sim {

/// Limit switches at both ends of an axis a lever moves at a speed (a hoist, a rope-luffed boom): the lever
/// is slowed ahead of them so the axis stops on them, and a push into one is counted.
class LimitSwitches {
 public:
  LimitSwitches(double lower, double upper) : lower_(lower), upper_(upper) {}

  /// `lever` in [-1, 1] (+ towards upper) at `position`; `full_speed` of the axis at full lever and its
  /// `deceleration` (units of the position per second, squared).
  double limit(double lever, double position, double full_speed, double deceleration, double dt_s) {
    lever = std::clamp(lever, -1.0, 1.0);
    const double room_up = std::max(0.0, upper_ - position), room_down = std::max(0.0, position - lower_);
    const bool pushing = (lever > 0.0 && room_up <= 0.01) || (lever < 0.0 && room_down <= 0.01);
    if (pushing && !at_limit_) ++hits_;
    at_limit_ = pushing;
    lever = std::min(lever, core::discrete_braking_speed(room_up, deceleration, dt_s) / full_speed);
    return std::max(lever, -core::discrete_braking_speed(room_down, deceleration, dt_s) / full_speed);
  }
  bool at_limit() const { return at_limit_; }
  std::uint32_t hits() const { return hits_; }
  void save_state(core::StateWriter& out) const { archive(*this, out); }
  void restore_state(core::StateReader& in) { archive(*this, in); }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar(self.at_limit_, self.hits_);
  }

  double lower_, upper_;
  bool at_limit_ = false;
  std::uint32_t hits_ = 0;
};

}  // namespace harbour::sim
