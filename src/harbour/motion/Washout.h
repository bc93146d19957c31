#pragma once

#include <array>

#include "harbour/core/Units.h"
#include "harbour/core/Vec3.h"
#include "harbour/motion/PlatformPose.h"
#include "harbour/motion/TransferFunction.h"

namespace harbour::motion {

/// Translational channel: scaled, limited specific force through a 2nd-order high-pass cascaded with a
/// 1st-order high-pass, integrated twice to a displacement.
struct TranslationalSettings {
  double gain = 0.5;           ///< [-] specific-force scale
  double limit_mps2 = 5.0;     ///< [m/s^2] input limit of the high-pass path
  double wn_rad_s = 1.25;      ///< [rad/s] 2nd-order high-pass natural frequency
  double zeta = 0.707;         ///< [-] its damping ratio
  double break_rad_s = 0.125;  ///< [rad/s] 1st-order high-pass break frequency
  /// [m/s^2] false-cue bound: platform acceleration against the demanded cue, or with none demanded (the
  /// washout's return), never exceeds this; a linear perception threshold (assumed 0.1)
  double false_cue_limit_mps2 = 0.1;
};

/// Tilt coordination: low-pass specific force rendered by tilting the cab against gravity.
struct TiltSettings {
  double gain = 0.5;              ///< [-]
  double limit_mps2 = 10.0;       ///< [m/s^2] input limit of the low-pass path
  double wn_rad_s = 1.25;         ///< [rad/s] 2nd-order low-pass natural frequency
  double zeta = 0.707;            ///< [-]
  double max_angle_rad = 0.175;   ///< [rad] largest tilt (10 deg)
  double max_rate_rad_s = 0.052;  ///< [rad/s] tilt rate below the perception threshold (3 deg/s)
};

/// Rotational channel: scaled, limited angular velocity through a 2nd-order high-pass, integrated to an
/// angle.
struct RotationalSettings {
  double gain = 0.5;         ///< [-]
  double limit_rad_s = 0.5;  ///< [rad/s] input limit
  double wn_rad_s = 5.0;     ///< [rad/s]
  double zeta = 0.707;       ///< [-]
};

/// Classical washout settings for one machine (Reid & Nahon); defaults are the published ones in
/// shared/data/reference.md.
struct WashoutSettings {
  double rate_hz = 100.0;  ///< [Hz] platform update rate (the filters' step)
  TranslationalSettings surge_sway;
  TranslationalSettings heave;
  TiltSettings tilt;
  RotationalSettings rotation;
};

/// What the occupant feels at the head point, in the cab frame (x forward, y left, z up).
struct MotionCue {
  core::Vec3 specific_force_mps2{0, 0, core::kStandardGravity};  ///< [m/s^2] a - g: (0, 0, g) at rest
  core::Vec3 angular_velocity_rad_s;                             ///< [rad/s]
};

/// Classical washout (Reid & Nahon 1985): specific force and angular velocity to a platform pose, each filter
/// discretised with the bilinear transform at the platform rate.
class ClassicalWashout {
 public:
  explicit ClassicalWashout(const WashoutSettings& settings);

  /// One platform step: the commanded pose (before workspace scaling and rate limits).
  PlatformPose step(const MotionCue& cue);
  void reset();

  /// The continuous transfer functions as implemented (for tests and docs).
  static ContinuousTf translation_to_displacement(const TranslationalSettings& s);
  static ContinuousTf tilt_low_pass(const TiltSettings& s);
  static ContinuousTf rotation_to_angle(const RotationalSettings& s);

  const WashoutSettings& settings() const { return settings_; }

 private:
  WashoutSettings settings_;
  double step_s_;
  // the platform's translation after the false-cue limit: takes the filter's acceleration while it is a
  // perceptible push the way the demanded cue goes (the onset); otherwise returns to neutral with bounded
  // acceleration
  struct Follower {
    double x = 0.0, v = 0.0;                      // [m], [m/s]
    double filtered_x1 = 0.0, filtered_x2 = 0.0;  // the filter's last two displacements [m]
  };
  double follow(Follower& f, double filtered_x, double cue, double limit) const;

  std::array<TustinFilter, 3> translation_;  // surge, sway, heave
  std::array<Follower, 3> followers_;
  std::array<TustinFilter, 2> tilt_;      // from surge and sway specific force
  std::array<TustinFilter, 3> rotation_;  // roll, pitch, yaw rates
  std::array<double, 2> tilt_angle_{};    // rate-limited tilt: roll (from sway), pitch (from surge)
};

}  // namespace harbour::motion
