#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "harbour/core/StateArchive.h"
#include "harbour/core/Vec3.h"
#include "harbour/sim/TwistlockEvent.h"

namespace harbour::sim {

/// Landing tolerances of the spreader's twistlocks in a container's top corner castings (settings).
struct TwistlockSettings {
  double lateral_tolerance_m = 0.03;  ///< [m] cone to aperture centre, horizontally (guide cones and flippers
                                      ///< bring the spreader within this; assumed)
  double landed_gap_m = 0.01;         ///< [m] spreader underside to casting top counted as landed (assumed)
};

/// What the cab lamps show.
struct TwistlockLamps {
  bool landed = false;  ///< all four corners seated
  bool locked = false;
  bool unlocked = false;
};

/// Corners (twistlock frame, x along the length: +x +y, -x +y, -x -y, +x -y) whose twistlock sits in the
/// matching corner casting of a container: the twistlock (at +-pin_half_length, +-pin_half_width on the
/// spreader's underside) within the lateral tolerance of the casting aperture (at +-aperture_half_length,
/// +-aperture_half_width on the container's top) and the underside within the landed gap of the top. Both
/// poses are world poses of the bottom-face / top-face centres, x along the length.
std::array<bool, 4> landed_corners(const core::Pose& spreader_underside, double pin_half_length_m,
                                   double pin_half_width_m, const core::Pose& container_top,
                                   double aperture_half_length_m, double aperture_half_width_m,
                                   const TwistlockSettings& settings);

/// The spreader's twistlocks with their interlocks: lock only when all four corners are landed; never unlock
/// under load; report misuse.
class Twistlocks {
 public:
  Twistlocks() { events_.reserve(16); }
  /// One control step of `dt_s`: the four landed sensors, the operator's buttons, and whether the load hangs
  /// from the spreader (hoist rope tension above the empty-spreader weight).
  void update(const std::array<bool, 4>& landed, bool lock_button, bool unlock_button, bool load_suspended,
              double dt_s);
  /// A landing ends when the spreader has been off the castings this long (the seated sensors flicker as the
  /// spreader settles, e.g. when the locks release its box).
  static constexpr double kLiftOff_s = 0.5;

  bool locked() const { return locked_; }
  TwistlockLamps lamps() const { return {all_landed_, locked_, !locked_}; }
  /// Events since the last call.
  std::vector<TwistlockEvent> take_events();
  void drain_events(std::vector<TwistlockEvent>& into) {
    into.insert(into.end(), events_.begin(), events_.end());
    events_.clear();
  }
  void save_state(core::StateWriter& out) const { archive(*this, out); }
  void restore_state(core::StateReader& in) {
    archive(*this, in);
    events_.clear();
  }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar(self.locked_, self.all_landed_, self.in_landing_, self.locked_this_landing_, self.lock_was_pressed_,
       self.unlock_was_pressed_, self.clear_s_);
  }

  bool locked_ = false;
  bool all_landed_ = false;
  bool in_landing_ = false;           // seated on a box, or off it for less than kLiftOff_s
  double clear_s_ = 0.0;              // [s] off the castings since
  bool locked_this_landing_ = false;  // the locks were closed at some point of the current landing
  bool lock_was_pressed_ = false, unlock_was_pressed_ = false;
  std::vector<TwistlockEvent> events_;
};

}  // namespace harbour::sim
