#include "harbour/motion/ShortCues.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::motion {
namespace {

// band-pass (2 zeta wn s) / (s^2 + 2 zeta wn s + wn^2): unit gain at the centre frequency
ContinuousTf band_pass(double wn, double zeta) {
  return {{0, 2 * zeta * wn, 0, 0}, {wn * wn, 2 * zeta * wn, 1, 0}, 2};
}

}  // namespace

ShortCues::ShortCues(const ShortCueSettings& settings, double step_s, std::uint64_t seed)
    : settings_(settings),
      step_s_(step_s),
      rng_(seed),
      roughness_(band_pass(2 * std::numbers::pi * settings.roughness_centre_hz, 0.5), step_s) {}

PlatformPose ShortCues::step(const ShortCueInputs& in) {
  PlatformPose cue;
  const double two_pi = 2 * std::numbers::pi;

  // engine: a sine at the firing frequency, amplitude with load
  const double hz = settings_.engine_idle_hz + std::clamp(in.engine_speed, 0.0, 1.0) *
                                                   (settings_.engine_max_hz - settings_.engine_idle_hz);
  engine_phase_ = std::fmod(engine_phase_ + two_pi * hz * step_s_, two_pi);
  cue[kHeave] +=
      settings_.engine_amplitude_m * std::clamp(in.engine_load, 0.0, 1.0) * std::sin(engine_phase_);

  // roughness: uniform white noise (unit variance) through a band-pass, scaled with ground speed
  const double noise = std::sqrt(12.0) * (rng_.uniform() - 0.5);
  cue[kHeave] += settings_.roughness_m_per_mps * std::abs(in.ground_speed_mps) * roughness_.step(noise);

  // impact: a velocity kick into a damped oscillator (semi-implicit Euler in 10 sub-steps)
  if (in.impact_speed_mps != 0.0)
    impact_velocity_ -=
        settings_.impact_m_per_mps * std::abs(in.impact_speed_mps) * two_pi * settings_.impact_hz;
  const double wn = two_pi * settings_.impact_hz, h = step_s_ / 10;
  for (int n = 0; n < 10; ++n) {
    impact_velocity_ +=
        (-wn * wn * impact_height_ - 2 * settings_.impact_damping * wn * impact_velocity_) * h;
    impact_height_ += impact_velocity_ * h;
  }
  cue[kHeave] += std::clamp(impact_height_, -settings_.impact_max_m, settings_.impact_max_m);
  return cue;
}

}  // namespace harbour::motion
