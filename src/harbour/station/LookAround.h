#pragma once

namespace harbour::station {

/// How far the operator can look round in the cab.
struct LookLimits {
  double yaw_rad = 1.92;    ///< left and right of the line of sight (110 degrees)
  double pitch_rad = 1.05;  ///< up and down (60 degrees)
};

/// The trainee turning the head in the cab without a tracker: keys held turn the view at a head's pace, a
/// mouse dragged with its button held turns it with the hand, and let go the view eases back to the cab's
/// line of sight. Within the cab's limits either way.
class LookAround {
 public:
  static constexpr double kTurn_radps = 1.57;        ///< a brisk head turn, 90 degrees a second
  static constexpr double kEaseBack_s = 0.3;         ///< let go, the view comes back with this time constant
  static constexpr double kDrag_rad_per_px = 0.004;  ///< a mouse drag across 400 pixels turns 92 degrees

  explicit LookAround(LookLimits limits) : limits_(limits) {}
  /// One frame's input: keys held (`yaw_keys` +1 left, -1 right; `pitch_keys` +1 up, -1 down), the mouse's
  /// movement since the last call while its button is held [pixels, right and down positive], over `dt_s`.
  void update(double dt_s, int yaw_keys, int pitch_keys, double drag_right_px, double drag_down_px,
              bool dragging);
  /// Straight back to the line of sight.
  void recentre() { yaw_rad_ = pitch_rad_ = 0.0; }
  double yaw_rad() const { return yaw_rad_; }
  double pitch_rad() const { return pitch_rad_; }

 private:
  LookLimits limits_;
  double yaw_rad_ = 0.0, pitch_rad_ = 0.0;
};

}  // namespace harbour::station
