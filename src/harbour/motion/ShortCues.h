#pragma once

#include "harbour/core/Rng.h"
#include "harbour/motion/PlatformPose.h"
#include "harbour/motion/TransferFunction.h"

namespace harbour::motion {

/// High-frequency cues added on top of the washout (settings, per machine).
struct ShortCueSettings {
  double engine_amplitude_m = 0.0005;   ///< [m] heave amplitude at full engine load
  double engine_idle_hz = 12.0;         ///< [Hz] firing frequency at idle
  double engine_max_hz = 35.0;          ///< [Hz] firing frequency at full speed
  double roughness_m_per_mps = 0.0004;  ///< [m per m/s] rms heave of driving roughness
  double roughness_centre_hz = 6.0;     ///< [Hz] centre of the roughness band
  double impact_m_per_mps = 0.01;       ///< [m per m/s] heave kick per impact speed
  double impact_max_m = 0.02;           ///< [m] largest impact excursion
  double impact_hz = 4.0;               ///< [Hz] ringing frequency of the cab after an impact
  double impact_damping = 0.3;          ///< [-] damping ratio of that ringing
};

/// What drives the short cues this step.
struct ShortCueInputs {
  double engine_load = 0.0;       ///< [-] 0..1
  double engine_speed = 0.0;      ///< [-] 0 idle .. 1 full speed
  double ground_speed_mps = 0.0;  ///< [m/s] of a wheeled machine
  double impact_speed_mps =
      0.0;  ///< [m/s] vertical speed of an impact this step (container landing, collision)
};

/// Engine vibration, driving roughness (band-limited noise from a seeded generator) and impact ringing.
class ShortCues {
 public:
  ShortCues(const ShortCueSettings& settings, double step_s, std::uint64_t seed = 1);
  /// The cue offset to add to the platform pose this step.
  PlatformPose step(const ShortCueInputs& inputs);

 private:
  ShortCueSettings settings_;
  double step_s_;
  core::Rng rng_;
  TustinFilter roughness_;
  double engine_phase_ = 0.0;     // [rad]
  double impact_height_ = 0.0;    // [m]
  double impact_velocity_ = 0.0;  // [m/s]
};

}  // namespace harbour::motion
