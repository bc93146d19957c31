#pragma once

#include <array>
#include <complex>
#include <cstdint>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::ig {

/// The fetch-limited JONSWAP spectrum of a wind sea (Hasselmann et al. 1973): with the dimensionless fetch
/// x = g F / U^2, alpha = 0.076 x^-0.22, omega_p = 22 (g / U) x^-0.33, gamma = 3.3.
struct Jonswap {
  double alpha = 0.0;
  double omega_peak_radps = 1.0;
  double gamma = 3.3;

  static Jonswap fetch_limited(double wind_mps, double fetch_m);
  /// S(omega) [m^2 s / rad].
  double density(double omega_radps) const;
  /// 4 sqrt(m0), integrated numerically over the whole spectrum.
  double significant_height_m() const;
};

/// A periodic patch of wind sea synthesised after Tessendorf (1999): Gaussian amplitudes from the JONSWAP
/// spectrum spread cos^2 about the wind, advanced by the deep-water dispersion omega^2 = g k and summed by
/// inverse FFTs (FFTW) into heights, slopes and the horizontal ("choppy") displacement on an N x N grid.
class OceanPatch {
 public:
  /// `n` a power of two; `length_m` the patch's side; the wind blows towards `wind_direction_rad`.
  OceanPatch(int n, double length_m, const Jonswap& spectrum, double wind_direction_rad, std::uint64_t seed);
  ~OceanPatch();
  OceanPatch(const OceanPatch&) = delete;
  OceanPatch& operator=(const OceanPatch&) = delete;

  /// Evaluates the surface at time t.
  void evaluate(double t_s);
  int size() const { return n_; }
  double length_m() const { return length_; }
  /// Height, slope (dh/dx, dh/dy) and choppy displacement at grid node (i, j) (x = i L / N, y = j L / N).
  double height(int i, int j) const { return height_[index(i, j)]; }
  /// Bilinear, periodic: at any point of the plane.
  double height_at(double x, double y) const { return sample(height_, x, y); }
  double slope_x_at(double x, double y) const { return sample(slope_x_, x, y); }
  double slope_y_at(double x, double y) const { return sample(slope_y_, x, y); }
  double displacement_x_at(double x, double y) const { return sample(shift_x_, x, y); }
  double displacement_y_at(double x, double y) const { return sample(shift_y_, x, y); }
  /// The variance the discrete spectrum carries (sum of S(k) dk^2 over the grid's wave numbers).
  double spectral_variance_m2() const { return spectral_variance_; }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(((j % n_) + n_) % n_) * static_cast<std::size_t>(n_) +
           static_cast<std::size_t>(((i % n_) + n_) % n_);
  }
  double sample(const std::vector<double>& field, double x, double y) const;
  void inverse_fft(std::vector<std::complex<double>>& spectrum, std::vector<double>& out);

  int n_;
  double length_;
  std::vector<std::complex<double>> h0_;  // h0(k) per grid wave number
  std::vector<double> omega_;
  std::vector<std::complex<double>> work_, buffer_;
  std::array<std::vector<std::complex<double>>, 5> spectra_;  // height, slopes, displacements
  std::vector<double> height_, slope_x_, slope_y_, shift_x_, shift_y_;
  double spectral_variance_ = 0.0;
  void* plan_ = nullptr;  // fftw_plan
};

/// The published swell's elevation above the still level at a world point at time t.
double swell_elevation_m(const scene::Snapshot::Sea& sea, double t_s, double x, double y);

/// Fresnel reflectance of water (n = 1.33) for unpolarised light at incidence cos_theta (from the normal).
double water_fresnel(double cos_theta);

}  // namespace harbour::ig
