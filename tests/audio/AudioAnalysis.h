#pragma once

// Measures of rendered sound for the tests: levels, the strongest tone in a band, a band's level.

#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace harbour::audio::test {

inline constexpr double kRate_hz = 48000.0;

/// One channel of interleaved samples.
inline std::vector<double> channel(const std::vector<float>& interleaved, int channels, int c) {
  std::vector<double> out;
  for (std::size_t n = static_cast<std::size_t>(c); n < interleaved.size();
       n += static_cast<std::size_t>(channels))
    out.push_back(interleaved[n]);
  return out;
}

inline std::size_t sample_at(double t_s) {
  return static_cast<std::size_t>(t_s * kRate_hz);
}

/// Root mean square over [from_s, to_s).
inline double rms(const std::vector<double>& x, double from_s, double to_s) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t n = sample_at(from_s); n < sample_at(to_s) && n < x.size(); ++n, ++count)
    sum += x[n] * x[n];
  return count ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

/// The largest magnitude over [from_s, to_s).
inline double peak(const std::vector<double>& x, double from_s, double to_s) {
  double most = 0.0;
  for (std::size_t n = sample_at(from_s); n < sample_at(to_s) && n < x.size(); ++n)
    most = std::max(most, std::abs(x[n]));
  return most;
}

/// The amplitude of the tone at `f_hz` over [from_s, to_s) (a Hann-windowed DFT bin).
inline double tone_amplitude(const std::vector<double>& x, double from_s, double to_s, double f_hz) {
  const std::size_t first = sample_at(from_s), last = std::min(sample_at(to_s), x.size());
  double re = 0.0, im = 0.0, window_sum = 0.0;
  for (std::size_t n = first; n < last; ++n) {
    const double u = static_cast<double>(n - first) / static_cast<double>(last - first);
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * u);
    const double phase = 2.0 * std::numbers::pi * f_hz * static_cast<double>(n) / kRate_hz;
    re += w * x[n] * std::cos(phase);
    im += w * x[n] * std::sin(phase);
    window_sum += w;
  }
  return window_sum > 0.0 ? 2.0 * std::hypot(re, im) / window_sum : 0.0;
}

/// The frequency of the strongest tone in [lo_hz, hi_hz] over [from_s, to_s), to `step_hz`.
inline double strongest_tone_hz(const std::vector<double>& x, double from_s, double to_s, double lo_hz,
                                double hi_hz, double step_hz = 0.5) {
  double best = lo_hz, most = -1.0;
  for (double f = lo_hz; f <= hi_hz; f += step_hz)
    if (const double a = tone_amplitude(x, from_s, to_s, f); a > most) most = a, best = f;
  return best;
}

}  // namespace harbour::audio::test
