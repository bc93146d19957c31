#include "harbour/motion/PlatformSequencer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::motion {
namespace {

// raised-cosine profile: zero velocity at both ends
double smooth(double t) {
  return 0.5 - 0.5 * std::cos(std::numbers::pi * std::clamp(t, 0.0, 1.0));
}

}  // namespace

PlatformSequencer::PlatformSequencer(const SequencerSettings& settings)
    : settings_(settings), pose_(settings.parked_pose), fader_(settings.fade_limits) {}

void PlatformSequencer::engage() {
  if (state_ != PlatformState::kParked) return;
  state_ = PlatformState::kEngaging;
  profile_start_ = pose_;
  progress_ = 0.0;
}

void PlatformSequencer::park() {
  if (state_ == PlatformState::kParked || state_ == PlatformState::kParking) return;
  state_ = PlatformState::kParking;
  profile_start_ = pose_;
  progress_ = 0.0;
}

const PlatformPose& PlatformSequencer::step(double dt_s, const PlatformPose& command, double command_age_s) {
  const bool fresh = command_age_s <= settings_.watchdog_timeout_s;
  switch (state_) {
    case PlatformState::kParked:
      pose_ = settings_.parked_pose;
      break;
    case PlatformState::kEngaging:
      progress_ += dt_s / settings_.engage_time_s;
      pose_ = profile_start_ * (1.0 - smooth(progress_));  // towards neutral (all zeros)
      if (progress_ >= 1.0) state_ = PlatformState::kEngaged;
      break;
    case PlatformState::kEngaged:
      if (fresh) {
        pose_ = command;
        break;
      }
      state_ = PlatformState::kFading;
      fader_.reset(pose_);
      [[fallthrough]];
    case PlatformState::kFading:
      if (fresh) {
        state_ = PlatformState::kEngaged;
        pose_ = command;
      } else {
        pose_ = fader_.step({}, dt_s);
      }
      break;
    case PlatformState::kParking:
      progress_ += dt_s / settings_.park_time_s;
      pose_ = profile_start_ + (settings_.parked_pose - profile_start_) * smooth(progress_);
      if (progress_ >= 1.0) state_ = PlatformState::kParked;
      break;
  }
  return pose_;
}

}  // namespace harbour::motion
