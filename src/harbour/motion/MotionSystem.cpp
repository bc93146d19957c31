#include "harbour/motion/MotionSystem.h"

namespace harbour::motion {

MotionSystem::MotionSystem(const MotionSettings& settings, std::uint64_t seed)
    : step_s_(1.0 / settings.washout.rate_hz),
      stroke_margin_m_(settings.stroke_margin_m),
      washout_(settings.washout),
      short_cues_(settings.short_cues, step_s_, seed),
      platform_(settings.geometry),
      limiter_(settings.limits) {}

PlatformFrame MotionSystem::step(const MotionCue& cue, const ShortCueInputs& short_cue_inputs) {
  PlatformFrame frame;
  // scale the whole demanded pose into the workspace: no single actuator is clipped, the cue keeps its shape
  const PlatformPose demanded = washout_.step(cue) + short_cues_.step(short_cue_inputs);
  frame.cue_scale = platform_.largest_reachable_scale(demanded, stroke_margin_m_);
  frame.pose = limiter_.step(demanded * frame.cue_scale, step_s_);
  frame.lengths = platform_.inverse(frame.pose);
  if (!platform_.reachable(frame.lengths)) {
    // the limiter left the workspace while following a moving target: pull the pose back along its direction
    ++workspace_interventions_;
    frame.pose = frame.pose * platform_.largest_reachable_scale(frame.pose);
    limiter_.reset(frame.pose);
    frame.lengths = platform_.inverse(frame.pose);
  }
  return frame;
}

}  // namespace harbour::motion
