#include "harbour/machines/parts/Twistlocks.h"

#include <cmath>

namespace harbour::sim {

std::array<bool, 4> landed_corners(const core::Pose& spreader_underside, double pin_half_length_m,
                                   double pin_half_width_m, const core::Pose& container_top,
                                   double aperture_half_length_m, double aperture_half_width_m,
                                   const TwistlockSettings& settings) {
  constexpr double kSign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  std::array<bool, 4> landed{};
  for (int c = 0; c < 4; ++c) {
    const core::Vec3 pin =
        spreader_underside.to_parent({kSign[c][0] * pin_half_length_m, kSign[c][1] * pin_half_width_m, 0.0});
    const core::Vec3 aperture{kSign[c][0] * aperture_half_length_m, kSign[c][1] * aperture_half_width_m, 0.0};
    const core::Vec3 in_container = container_top.to_local(pin);
    const double lateral = std::hypot(in_container.x - aperture.x, in_container.y - aperture.y);
    landed[c] = lateral <= settings.lateral_tolerance_m && std::abs(in_container.z) <= settings.landed_gap_m;
  }
  return landed;
}

void Twistlocks::update(const std::array<bool, 4>& landed, bool lock_button, bool unlock_button,
                        bool load_suspended, double dt_s) {
  all_landed_ = landed[0] && landed[1] && landed[2] && landed[3];
  const bool lock_pressed = lock_button && !lock_was_pressed_;
  const bool unlock_pressed = unlock_button && !unlock_was_pressed_;
  lock_was_pressed_ = lock_button;
  unlock_was_pressed_ = unlock_button;

  if (lock_pressed && !locked_) {
    if (all_landed_)
      locked_ = true;
    else
      events_.push_back(TwistlockEvent::kLockRefusedNotLanded);
  }
  if (unlock_pressed && locked_) {
    if (load_suspended)
      events_.push_back(TwistlockEvent::kUnlockRefusedSuspended);
    else
      locked_ = false;
  }
  // lifting off a landing during which the locks never closed is a pick-up hoisted unlocked; a set-down
  // closes them on arrival (or they stay closed through a carry), unlocks and lifts away: the normal end of a
  // move
  if (all_landed_) {
    if (!in_landing_) locked_this_landing_ = false;
    in_landing_ = true;
    clear_s_ = 0.0;
    if (locked_) locked_this_landing_ = true;
  } else if (in_landing_) {
    clear_s_ += dt_s;
    if (clear_s_ >= kLiftOff_s) {
      in_landing_ = false;
      if (!locked_ && !locked_this_landing_) events_.push_back(TwistlockEvent::kHoistedUnlocked);
    }
  }
}

std::vector<TwistlockEvent> Twistlocks::take_events() {
  std::vector<TwistlockEvent> out;
  drain_events(out);
  return out;
}

}  // namespace harbour::sim
