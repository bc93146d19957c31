#include "harbour/ig/Ocean.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "harbour/core/Rng.h"

namespace harbour::ig {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;
std::mutex fftw_planner;  // FFTW's planner is not thread-safe; each image generator plans its own patch

double gaussian(core::Rng& rng) {  // Box-Muller
  const double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}
}  // namespace

Jonswap Jonswap::fetch_limited(double wind_mps, double fetch_m) {
  const double u = std::max(wind_mps, 0.5), x = kG * std::max(fetch_m, 1.0) / (u * u);
  Jonswap j;
  j.alpha = 0.076 * std::pow(x, -0.22);
  j.omega_peak_radps = 22.0 * (kG / u) * std::pow(x, -0.33);
  return j;
}

double Jonswap::density(double omega) const {
  if (omega <= 0.0) return 0.0;
  const double sigma = omega <= omega_peak_radps ? 0.07 : 0.09;
  const double d = (omega - omega_peak_radps) / (sigma * omega_peak_radps);
  const double ratio = omega_peak_radps / omega;
  return alpha * kG * kG * std::pow(omega, -5.0) * std::exp(-1.25 * ratio * ratio * ratio * ratio) *
         std::pow(gamma, std::exp(-0.5 * d * d));
}

double Jonswap::significant_height_m() const {
  double m0 = 0.0;
  const double step = omega_peak_radps / 2000.0;
  for (double w = step / 2.0; w < 20.0 * omega_peak_radps; w += step)
    m0 += density(w) * step;
  return 4.0 * std::sqrt(m0);
}

OceanPatch::OceanPatch(int n, double length_m, const Jonswap& spectrum, double wind_direction_rad,
                       std::uint64_t seed)
    : n_(n), length_(length_m) {
  if (n < 4 || (n & (n - 1)) != 0)
    throw std::invalid_argument("ocean patch: the grid must be a power of two");
  if (!(length_m > 0.0)) throw std::invalid_argument("ocean patch: the length must be positive");
  const std::size_t cells = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  h0_.assign(cells, {});
  omega_.assign(cells, 0.0);
  work_.assign(cells, {});
  buffer_.assign(cells, {});
  for (auto* field : {&height_, &slope_x_, &slope_y_, &shift_x_, &shift_y_})
    field->assign(cells, 0.0);
  core::Rng rng(seed);
  const double dk = 2.0 * kPi / length_m;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double xi_r = gaussian(rng), xi_i = gaussian(rng);  // drawn for every node: a fixed sequence
      const int mi = i < n / 2 ? i : i - n, mj = j < n / 2 ? j : j - n;
      if ((mi == 0 && mj == 0) || mi == -n / 2 || mj == -n / 2) continue;  // no mean, no Nyquist
      const double kx = mi * dk, ky = mj * dk, k = std::hypot(kx, ky);
      const double omega = std::sqrt(kG * k);
      const double off_wind = std::atan2(ky, kx) - wind_direction_rad;
      const double c = std::cos(off_wind);
      const double spreading = c > 0.0 ? 2.0 / kPi * c * c : 0.0;  // cos^2 over the half-plane downwind
      // S(kx, ky) dkx dky = S(omega) D(theta) domega dtheta, with domega/dk = g / (2 omega), dkx dky = k dk
      // dtheta
      const double s_k = spectrum.density(omega) * spreading * (kG / (2.0 * omega)) / k;
      const double variance = s_k * dk * dk;
      spectral_variance_ += variance;
      h0_[index(i, j)] = std::complex<double>(xi_r, xi_i) * std::sqrt(variance / 4.0);  // E|h0|^2 = P / 2
      omega_[index(i, j)] = omega;
    }
  const std::lock_guard lock(fftw_planner);
  plan_ = fftw_plan_dft_2d(n, n, reinterpret_cast<fftw_complex*>(work_.data()),
                           reinterpret_cast<fftw_complex*>(buffer_.data()), FFTW_BACKWARD, FFTW_ESTIMATE);
}

OceanPatch::~OceanPatch() {
  const std::lock_guard lock(fftw_planner);
  fftw_destroy_plan(static_cast<fftw_plan>(plan_));
}

void OceanPatch::inverse_fft(std::vector<std::complex<double>>& spectrum, std::vector<double>& out) {
  work_.swap(spectrum);  // the plan reads work_
  fftw_execute_dft(static_cast<fftw_plan>(plan_), reinterpret_cast<fftw_complex*>(work_.data()),
                   reinterpret_cast<fftw_complex*>(buffer_.data()));
  work_.swap(spectrum);
  for (std::size_t c = 0; c < out.size(); ++c)
    out[c] = buffer_[c].real();  // the spectrum is Hermitian: the imaginary part is rounding
}

void OceanPatch::evaluate(double t) {
  const double dk = 2.0 * kPi / length_;
  const std::size_t cells = h0_.size();
  for (auto& spectrum : spectra_)
    spectrum.resize(cells);
  auto& [h, sx, sy, dx, dy] = spectra_;
  const std::complex<double> i_unit(0.0, 1.0);
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i) {
      const std::size_t c = index(i, j), mirror = index(-i, -j);
      // h(k, t) = h0(k) e^{-i w t} + conj(h0(-k)) e^{i w t}: the h0(k) part travels along +k
      const std::complex<double> turn = std::polar(1.0, -omega_[c] * t);
      const std::complex<double> hk = h0_[c] * turn + std::conj(h0_[mirror]) * std::conj(turn);
      const int mi = i < n_ / 2 ? i : i - n_, mj = j < n_ / 2 ? j : j - n_;
      const double kx = mi * dk, ky = mj * dk, k = std::hypot(kx, ky);
      h[c] = hk;
      sx[c] = i_unit * kx * hk;
      sy[c] = i_unit * ky * hk;
      dx[c] = k > 0.0 ? i_unit * (kx / k) * hk : 0.0;  // towards the crests (Gerstner's sense)
      dy[c] = k > 0.0 ? i_unit * (ky / k) * hk : 0.0;
    }
  inverse_fft(h, height_);
  inverse_fft(sx, slope_x_);
  inverse_fft(sy, slope_y_);
  inverse_fft(dx, shift_x_);
  inverse_fft(dy, shift_y_);
}

double OceanPatch::sample(const std::vector<double>& field, double x, double y) const {
  const double u = x / length_ * n_, v = y / length_ * n_;
  const double fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(std::fmod(fu, n_)), j = static_cast<int>(std::fmod(fv, n_));
  const double a = u - fu, b = v - fv;
  return (1 - a) * (1 - b) * field[index(i, j)] + a * (1 - b) * field[index(i + 1, j)] +
         (1 - a) * b * field[index(i, j + 1)] + a * b * field[index(i + 1, j + 1)];
}

double swell_elevation_m(const scene::Snapshot::Sea& s, double t, double x, double y) {
  double eta = 0.0;
  for (int n = 0; n < s.swell_count; ++n) {
    const scene::Snapshot::Swell& w = s.swells[static_cast<std::size_t>(n)];
    const double omega = 2.0 * kPi / w.period_s, k = omega * omega / kG;  // deep water
    const double along =
        (x - s.reference_m.x) * std::cos(w.direction_rad) + (y - s.reference_m.y) * std::sin(w.direction_rad);
    eta += w.amplitude_m * std::sin(omega * t + w.phase_rad - k * along);
  }
  return eta;
}

double water_fresnel(double cos_theta) {
  constexpr double n = 1.33;
  const double ci = std::clamp(cos_theta, 0.0, 1.0);
  const double st = std::sqrt(1.0 - ci * ci) / n, ct = std::sqrt(1.0 - st * st);
  const double rs = (ci - n * ct) / (ci + n * ct), rp = (ct - n * ci) / (ct + n * ci);
  return 0.5 * (rs * rs + rp * rp);  // unpolarised light
}

}  // namespace harbour::ig
