#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "harbour/ig/Ocean.h"

using harbour::ig::Jonswap;
using harbour::ig::OceanPatch;

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;

double patch_variance(const OceanPatch& p) {
  double sum = 0.0, sum2 = 0.0;
  for (int j = 0; j < p.size(); ++j)
    for (int i = 0; i < p.size(); ++i) {
      sum += p.height(i, j);
      sum2 += p.height(i, j) * p.height(i, j);
    }
  const double n = p.size() * p.size();
  return sum2 / n - (sum / n) * (sum / n);
}
}  // namespace

// The fetch-limited JONSWAP sea carries the energy of the published fetch law: Hs = 1.6e-3 U^2/g (gF/U^2)^1/2
// (Hasselmann et al. 1973; CERC Shore Protection Manual / Coastal Engineering Manual II-2), within 10 %.
TEST(Ocean, TheWindSeaHasTheSignificantHeightOfTheFetchLaw) {
  for (const auto& [wind, fetch] :
       {std::pair{10.0, 2000.0}, std::pair{15.0, 5000.0}, std::pair{6.0, 1000.0}}) {
    const double law = 1.6e-3 * wind * wind / kG * std::sqrt(kG * fetch / (wind * wind));
    EXPECT_NEAR(Jonswap::fetch_limited(wind, fetch).significant_height_m(), law, 0.10 * law)
        << wind << " m/s over " << fetch << " m";
  }
}

// Parseval: the synthesised surface's variance is the variance the discrete spectrum carries, and the grid
// (ten peak wavelengths, 128 nodes) resolves all but the far tail of the spectrum.
TEST(Ocean, TheSurfaceCarriesTheSpectrumsVariance) {
  const Jonswap sea = Jonswap::fetch_limited(10.0, 2000.0);
  const double peak_wavelength = 2.0 * kPi * kG / (sea.omega_peak_radps * sea.omega_peak_radps);
  OceanPatch patch(128, 10.0 * peak_wavelength, sea, 0.3, 7);
  const double m0 = std::pow(sea.significant_height_m() / 4.0, 2.0);
  EXPECT_GT(patch.spectral_variance_m2(), 0.85 * m0);
  EXPECT_LT(patch.spectral_variance_m2(), 1.01 * m0);
  // one realisation: its variance scatters about the expectation (many independent modes: a few per cent)
  double mean_variance = 0.0;
  for (const double t : {0.0, 7.3, 19.1, 40.7}) {
    patch.evaluate(t);
    mean_variance += patch_variance(patch) / 4.0;
  }
  EXPECT_NEAR(mean_variance, patch.spectral_variance_m2(), 0.15 * patch.spectral_variance_m2());
}

// The waves run downwind at the deep-water phase speed: the surface a short time later, shifted back by c dt
// along the wind, correlates with the surface before better than when shifted the other way.
TEST(Ocean, WavesTravelDownwind) {
  const Jonswap sea = Jonswap::fetch_limited(10.0, 2000.0);
  const double peak_wavelength = 2.0 * kPi * kG / (sea.omega_peak_radps * sea.omega_peak_radps);
  const double wind_direction = 0.0;  // towards +x
  OceanPatch patch(64, 8.0 * peak_wavelength, sea, wind_direction, 3);
  const double c = kG / sea.omega_peak_radps, dt = 0.15 * peak_wavelength / c;
  patch.evaluate(10.0);
  std::vector<double> before;
  const double step = patch.length_m() / 64.0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      before.push_back(patch.height_at(i * step, j * step));
  patch.evaluate(10.0 + dt);
  const auto correlation = [&](double shift) {
    double s = 0.0;
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        s += before[static_cast<std::size_t>(j * 64 + i)] * patch.height_at(i * step + shift, j * step);
    return s;
  };
  EXPECT_GT(correlation(c * dt), 1.5 * std::abs(correlation(-c * dt)));
}

// The swell through the reference point is the vessel's heave there, and a crest half a wavelength away is a
// trough.
TEST(Ocean, TheSwellRisesWithTheVesselsHeave) {
  harbour::scene::Snapshot::Sea s;
  s.reference_m = {31.0, 0.0, -3.5};
  s.swell_count = 1;
  s.swells[0] = {0.4, 8.0, 0.3, kPi};
  const double wavelength = kG * 64.0 / (2.0 * kPi);
  for (const double t : {0.0, 1.3, 5.9}) {
    const double heave = 0.4 * std::sin(2.0 * kPi * t / 8.0 + 0.3);
    EXPECT_NEAR(harbour::ig::swell_elevation_m(s, t, 31.0, 25.0), heave, 1e-12);
    EXPECT_NEAR(harbour::ig::swell_elevation_m(s, t, 31.0 - wavelength / 2.0, 0.0), -heave, 1e-9);
  }
}

// Fresnel for water: 2 % looking straight down ((n-1)/(n+1))^2, all of it at grazing incidence, and at
// Brewster's angle (tan = 1.33) only the s-polarised half: cos^2(2 theta_B) / 2.
TEST(Ocean, WaterReflectsLittleFromAboveAndAllAtGrazing) {
  EXPECT_NEAR(harbour::ig::water_fresnel(1.0), 0.33 * 0.33 / (2.33 * 2.33), 1e-9);
  EXPECT_NEAR(harbour::ig::water_fresnel(0.0), 1.0, 1e-9);
  const double brewster = std::atan(1.33);
  EXPECT_NEAR(harbour::ig::water_fresnel(std::cos(brewster)), std::pow(std::cos(2.0 * brewster), 2.0) / 2.0,
              1e-9);
}
