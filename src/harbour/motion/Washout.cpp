#include "harbour/motion/Washout.h"

#include <algorithm>
#include <cmath>

#include "harbour/core/Braking.h"
#include "harbour/core/Units.h"

namespace harbour::motion {

ContinuousTf ClassicalWashout::translation_to_displacement(const TranslationalSettings& s) {
  // acceleration -> high-pass 2nd x high-pass 1st -> 1/s^2: s / ((s^2 + 2 zeta wn s + wn^2)(s + wb))
  return ContinuousTf::cascade(ContinuousTf::high_pass2(s.wn_rad_s, s.zeta),
                               ContinuousTf::high_pass1(s.break_rad_s))
      .integrated(2);
}

ContinuousTf ClassicalWashout::tilt_low_pass(const TiltSettings& s) {
  return ContinuousTf::low_pass2(s.wn_rad_s, s.zeta);
}

ContinuousTf ClassicalWashout::rotation_to_angle(const RotationalSettings& s) {
  // angular rate -> high-pass 2nd -> 1/s: s / (s^2 + 2 zeta wn s + wn^2)
  return ContinuousTf::high_pass2(s.wn_rad_s, s.zeta).integrated(1);
}

ClassicalWashout::ClassicalWashout(const WashoutSettings& settings)
    : settings_(settings), step_s_(1.0 / settings.rate_hz) {
  for (int i = 0; i < 2; ++i)
    translation_[i] = TustinFilter(translation_to_displacement(settings.surge_sway), step_s_);
  translation_[2] = TustinFilter(translation_to_displacement(settings.heave), step_s_);
  for (auto& f : tilt_)
    f = TustinFilter(tilt_low_pass(settings.tilt), step_s_);
  for (auto& f : rotation_)
    f = TustinFilter(rotation_to_angle(settings.rotation), step_s_);
}

void ClassicalWashout::reset() {
  for (auto& f : translation_)
    f.reset();
  for (auto& f : tilt_)
    f.reset();
  for (auto& f : rotation_)
    f.reset();
  followers_ = {};
  tilt_angle_ = {};
}

double ClassicalWashout::follow(Follower& f, double filtered_x, double cue, double limit) const {
  // the filter's acceleration (second difference of its displacement)
  const double dt = step_s_;
  const double filter_a = (filtered_x - 2.0 * f.filtered_x1 + f.filtered_x2) / (dt * dt);
  f.filtered_x2 = f.filtered_x1;
  f.filtered_x1 = filtered_x;
  double a = filter_a;
  if (!(filter_a * cue > 0.0 && std::abs(filter_a) > limit)) {
    // no perceptible onset (no cue, the filter braking against it, or its sub-threshold tail): head for
    // neutral at no more than the limit, braking in time
    const double brake = core::discrete_braking_speed(std::abs(f.x), limit, dt);
    const double v_wanted = std::clamp(-f.x / dt, -brake, brake);
    a = std::clamp((v_wanted - f.v) / dt, -limit, limit);
  }
  f.v += a * dt;
  f.x += f.v * dt;
  return f.x;
}

PlatformPose ClassicalWashout::step(const MotionCue& cue) {
  PlatformPose pose;
  const core::Vec3 f = cue.specific_force_mps2;
  const double g = core::kStandardGravity;

  // translational: onset cues of specific force (gravity removed from heave)
  const double translational_in[3] = {f.x, f.y, f.z - g};
  for (int i = 0; i < 3; ++i) {
    const TranslationalSettings& s = i < 2 ? settings_.surge_sway : settings_.heave;
    const double demanded = std::clamp(s.gain * translational_in[i], -s.limit_mps2, s.limit_mps2);
    pose[kSurge + i] =
        follow(followers_[i], translation_[i].step(demanded), demanded, s.false_cue_limit_mps2);
  }

  // tilt coordination: sustained surge/sway specific force rendered by gravity; f_x = -g sin(pitch),
  // f_y = g sin(roll); rate-limited below the rotation perception threshold
  const TiltSettings& t = settings_.tilt;
  const double sustained_x = tilt_[0].step(std::clamp(t.gain * f.x, -t.limit_mps2, t.limit_mps2));
  const double sustained_y = tilt_[1].step(std::clamp(t.gain * f.y, -t.limit_mps2, t.limit_mps2));
  const double max_sin = std::sin(t.max_angle_rad);
  const double target_pitch = -std::asin(std::clamp(sustained_x / g, -max_sin, max_sin));
  const double target_roll = std::asin(std::clamp(sustained_y / g, -max_sin, max_sin));
  const double max_change = t.max_rate_rad_s * step_s_;
  tilt_angle_[0] += std::clamp(target_roll - tilt_angle_[0], -max_change, max_change);
  tilt_angle_[1] += std::clamp(target_pitch - tilt_angle_[1], -max_change, max_change);

  // rotational: onset of angular velocity
  const RotationalSettings& r = settings_.rotation;
  const double w[3] = {cue.angular_velocity_rad_s.x, cue.angular_velocity_rad_s.y,
                       cue.angular_velocity_rad_s.z};
  for (int i = 0; i < 3; ++i)
    pose[kRoll + i] = rotation_[i].step(std::clamp(r.gain * w[i], -r.limit_rad_s, r.limit_rad_s));
  pose[kRoll] += tilt_angle_[0];
  pose[kPitch] += tilt_angle_[1];
  return pose;
}

}  // namespace harbour::motion
