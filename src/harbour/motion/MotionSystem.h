#pragma once

#include "harbour/motion/MotionLimiter.h"
#include "harbour/motion/ShortCues.h"
#include "harbour/motion/StewartPlatform.h"
#include "harbour/motion/Washout.h"

namespace harbour::motion {

/// Everything that describes one cabin on one platform (settings, loaded from data/motion/).
struct MotionSettings {
  WashoutSettings washout;
  ShortCueSettings short_cues;
  StewartGeometry geometry;
  MotionLimits limits;
  double stroke_margin_m = 0.03;  ///< [m] cues are scaled into the stroke less this at each end, leaving room
                                  ///< for the rate limiter to trail a moving target
};

/// One platform update: the pose sent and the actuator lengths it needs.
struct PlatformFrame {
  PlatformPose pose;
  ActuatorLengths lengths{};
  double cue_scale = 1.0;  ///< [-] share of the washout cue that fitted the workspace (1: all of it)
};

/// The cueing pipeline: washout + short cues, scaled as a whole into the actuator workspace, then held to the
/// platform's per-axis velocity and acceleration limits, then inverse kinematics.
class MotionSystem {
 public:
  explicit MotionSystem(const MotionSettings& settings, std::uint64_t seed = 1);

  /// One platform step (at settings.washout.rate_hz).
  PlatformFrame step(const MotionCue& cue, const ShortCueInputs& short_cue_inputs = {});
  const StewartPlatform& platform() const { return platform_; }
  /// Steps where the rate-limited pose left the stroke and was pulled back along its direction (a jolt the
  /// limits could not prevent); shown to the instructor, expected to stay rare.
  long workspace_interventions() const { return workspace_interventions_; }
  double step_s() const { return step_s_; }

 private:
  double step_s_;
  double stroke_margin_m_;
  ClassicalWashout washout_;
  ShortCues short_cues_;
  StewartPlatform platform_;
  MotionLimiter limiter_;
  long workspace_interventions_ = 0;
};

}  // namespace harbour::motion
