#include "harbour/station/LookAround.h"

#include <algorithm>
#include <cmath>

namespace harbour::station {

void LookAround::update(double dt_s, int yaw_keys, int pitch_keys, double drag_right_px, double drag_down_px,
                        bool dragging) {
  if (!(dt_s > 0.0)) return;
  const bool holding = yaw_keys != 0 || pitch_keys != 0 || dragging;
  if (holding) {
    // the keys at a head's pace; the mouse as far as the hand moves it (right turns right, down looks down)
    yaw_rad_ += std::clamp(yaw_keys, -1, 1) * kTurn_radps * dt_s - drag_right_px * kDrag_rad_per_px;
    pitch_rad_ += std::clamp(pitch_keys, -1, 1) * kTurn_radps * dt_s - drag_down_px * kDrag_rad_per_px;
  } else {
    const double keep = std::exp(-dt_s / kEaseBack_s);
    yaw_rad_ *= keep;
    pitch_rad_ *= keep;
    if (std::abs(yaw_rad_) < 1e-4 && std::abs(pitch_rad_) < 1e-4) yaw_rad_ = pitch_rad_ = 0.0;
  }
  yaw_rad_ = std::clamp(yaw_rad_, -limits_.yaw_rad, limits_.yaw_rad);
  pitch_rad_ = std::clamp(pitch_rad_, -limits_.pitch_rad, limits_.pitch_rad);
}

}  // namespace harbour::station
