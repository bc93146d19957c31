#include "harbour/ig/Sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::ig {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEarthRadius_km = 6371.0;
constexpr double kOzoneHeight_km = 22.0;  // the ozone layer's centroid (the WMO's ozone air mass)
// the ozone's optical depth at 680, 550 and 440 nm for a column of 300 DU (Chappuis band: cross sections
// 2.0e-21, 3.3e-21 and 0.25e-21 cm² times 8.07e18 molecules/cm²)
constexpr core::Vec3 kOzoneDepth{0.016, 0.027, 0.002};
constexpr core::Vec3 kWavelength_um{0.680, 0.550, 0.440};
constexpr double kSolarIlluminance_lx = 127500.0;  // outside the atmosphere
// the eye's adaptation: it settles on L_a = Y_zenith^p L_ref^(1-p), partly following the sky's brightness
constexpr double kAdaptation = 0.6;
constexpr double kAdaptationReference_cd_m2 = 6000.0;
constexpr double kSkyKey = 0.25;  // a sky of luminance L shows as 1 - exp(-kSkyKey L / L_a) (linear)
constexpr double kSceneKey =
    0.071;  // a white surface under illuminance E shows as kSceneKey E / L_a (linear)
constexpr double kNightAmbient = 0.08;  // moon, stars and the town's glow on the scene at night (display)
constexpr double kGamma = 2.2;
constexpr double kGroundAlbedo = 0.3;  // concrete paving (assumed)

double encode(double linear) {
  return std::pow(std::max(linear, 0.0), 1.0 / kGamma);
}
core::Vec3 encode(const core::Vec3& c) {
  return {encode(c.x), encode(c.y), encode(c.z)};
}
double luminance(const core::Vec3& rgb) {
  return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
}
core::Vec3 times(const core::Vec3& a, const core::Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
core::Vec3 exp_of(const core::Vec3& c) {
  return {std::exp(c.x), std::exp(c.y), std::exp(c.z)};
}

// the sun's zenith-angle polynomial of a zenith chromaticity: [T² T 1] M [θ³ θ² θ 1]ᵀ
double zenith_chromaticity(const std::array<std::array<double, 4>, 3>& m, double turbidity, double theta) {
  const std::array<double, 3> t{turbidity * turbidity, turbidity, 1.0};
  const std::array<double, 4> th{theta * theta * theta, theta * theta, theta, 1.0};
  double sum = 0.0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      sum += t[i] * m[i][j] * th[j];
  return sum;
}

// the ozone layer's air mass for a sun at zenith angle θ (a shell at kOzoneHeight_km)
double ozone_air_mass(double cos_theta) {
  const double h = kOzoneHeight_km / kEarthRadius_km;
  return (1.0 + h) / std::sqrt(cos_theta * cos_theta + 2.0 * h);
}

}  // namespace

double relative_air_mass(double elevation) {
  const double deg = elevation * 180.0 / kPi;
  return 1.0 / (std::sin(elevation) + 0.50572 * std::pow(std::max(deg + 6.07995, 1e-3), -1.6364));
}

double twilight_dimming(double depression_deg) {
  const double d = std::clamp(depression_deg, 0.0, 18.0);
  return std::pow(10.0, -0.42 * std::min(d, 12.0) - 0.23 * std::max(d - 12.0, 0.0));
}

core::Vec3 linear_srgb(const core::Vec3& xyY) {
  const double y = std::max(xyY.y, 1e-9);
  const double X = xyY.x / y * xyY.z, Y = xyY.z, Z = (1.0 - xyY.x - xyY.y) / y * xyY.z;
  return {3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
          0.0557 * X - 0.2040 * Y + 1.0570 * Z};
}

core::Vec3 sun_beam_transmittance(double elevation, double turbidity) {
  if (elevation < -0.01) return {};
  const double m = relative_air_mass(elevation);
  const double beta = 0.04608 * turbidity - 0.04586;
  const auto depth = [&](double lambda_um, double ozone) {
    return 0.008735 * std::pow(lambda_um, -4.08) + beta * std::pow(lambda_um, -1.3) + ozone;
  };
  const double oz_m = ozone_air_mass(std::sin(std::max(elevation, 0.0))) / m;  // the ozone's own path
  return exp_of(core::Vec3{-m * depth(kWavelength_um.x, kOzoneDepth.x * oz_m),
                           -m * depth(kWavelength_um.y, kOzoneDepth.y * oz_m),
                           -m * depth(kWavelength_um.z, kOzoneDepth.z * oz_m)});
}

ClearSky::ClearSky(const core::Vec3& to_sun, double turbidity) {
  const double elevation = std::asin(std::clamp(to_sun.z, -1.0, 1.0));
  const double horizontal = std::hypot(to_sun.x, to_sun.y);
  const core::Vec3 flat = horizontal > 1e-9 ? core::Vec3{to_sun.x / horizontal, to_sun.y / horizontal, 0.0}
                                            : core::Vec3{1.0, 0.0, 0.0};
  // the distribution of a sun no lower than the horizon (Perez's fit ends there)
  sun_ = elevation >= 0.0 ? to_sun : flat;
  sun_theta_ = std::acos(std::clamp(sun_.z, 0.0, 1.0));
  twilight_ = twilight_dimming(-elevation * 180.0 / kPi);
  const double t = turbidity;
  y_lum_ = {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771,
            -0.0670 * t + 0.3703};
  x_chroma_ = {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989,
               -0.0033 * t + 0.0452};
  y_chroma_ = {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537,
               -0.0109 * t + 0.0529};
  const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * sun_theta_);
  zenith_.z = ((4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192) * 1000.0;  // kcd/m² to cd/m²
  zenith_.x = zenith_chromaticity({{{0.00166, -0.00375, 0.00209, 0.0},
                                    {-0.02903, 0.06377, -0.03202, 0.00394},
                                    {0.11693, -0.21196, 0.06052, 0.25886}}},
                                  t, sun_theta_);
  zenith_.y = zenith_chromaticity({{{0.00275, -0.00610, 0.00317, 0.0},
                                    {-0.04214, 0.08970, -0.04153, 0.00516},
                                    {0.15346, -0.26756, 0.06670, 0.26688}}},
                                  t, sun_theta_);
  at_zenith_lum_ = perez(y_lum_, 1.0, sun_theta_);
  at_zenith_x_ = perez(x_chroma_, 1.0, sun_theta_);
  at_zenith_y_ = perez(y_chroma_, 1.0, sun_theta_);
  // the light the sky scatters crossed the ozone on the sun's path; twilight's tangential paths are longer
  // (assumed: three more layer thicknesses a degree of depression)
  const double ozone_mass =
      ozone_air_mass(std::max(to_sun.z, 0.0)) + 3.0 * std::max(-elevation * 180.0 / kPi, 0.0);
  ozone_ = exp_of(kOzoneDepth * -ozone_mass);
}

double ClearSky::perez(const Perez& c, double cos_theta, double gamma) {
  const double cos_gamma = std::cos(gamma);
  return (1.0 + c[0] * std::exp(c[1] / std::max(cos_theta, 0.01))) *
         (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

double ClearSky::gamma_to(const core::Vec3& d) const {
  return std::acos(std::clamp(dot(d, sun_), -1.0, 1.0));
}

double ClearSky::relative_luminance(const core::Vec3& d) const {
  return perez(y_lum_, std::max(d.z, 0.0), gamma_to(d)) / at_zenith_lum_;
}

core::Vec3 ClearSky::xyY(const core::Vec3& d) const {
  const double cos_theta = std::max(d.z, 0.0), gamma = gamma_to(d);
  return {zenith_.x * perez(x_chroma_, cos_theta, gamma) / at_zenith_x_,
          zenith_.y * perez(y_chroma_, cos_theta, gamma) / at_zenith_y_,
          zenith_.z * twilight_ * perez(y_lum_, cos_theta, gamma) / at_zenith_lum_};
}

core::Vec3 ClearSky::radiance(const core::Vec3& d) const {
  return times(linear_srgb(xyY(d)), ozone_);
}

namespace {

struct Illuminance {
  core::Vec3 sky, sun;  // lux per channel on a surface facing up (the sky) and facing the sun (the sun)
};
// the sky's light on a horizontal surface, E = ∫ L cos θ dω over the hemisphere (8 rings, 24 azimuths), and
// the sun's beam
Illuminance illuminance(const ClearSky& sky, const core::Vec3& to_sun, double turbidity) {
  constexpr int kRings = 8, kAzimuths = 24;
  Illuminance e;
  for (int r = 0; r < kRings; ++r) {
    const double theta = (r + 0.5) / kRings * kPi / 2.0;
    const double weight = std::cos(theta) * std::sin(theta) * (kPi / 2.0 / kRings) * (2.0 * kPi / kAzimuths);
    for (int a = 0; a < kAzimuths; ++a) {
      const double phi = (a + 0.5) / kAzimuths * 2.0 * kPi;
      e.sky +=
          sky.radiance({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)}) *
          weight;
    }
  }
  e.sun =
      sun_beam_transmittance(std::asin(std::clamp(to_sun.z, -1.0, 1.0)), turbidity) * kSolarIlluminance_lx;
  return e;
}

// the daylight of a sun 60° up: its beam and the sky's light together
core::Vec3 white_daylight(double turbidity) {
  const core::Vec3 high_sun{0.5, 0.0, std::sqrt(0.75)};
  const Illuminance reference = illuminance(ClearSky(high_sun, turbidity), high_sun, turbidity);
  return reference.sky + reference.sun;
}

}  // namespace

Daylight::Daylight(const core::Vec3& to_sun, double turbidity) : sky_(to_sun, turbidity) {
  adapted_ = std::pow(std::max(sky_.zenith_luminance(), 1e-4), kAdaptation) *
             std::pow(kAdaptationReference_cd_m2, 1.0 - kAdaptation);
  constexpr int kAzimuths = 24;
  const double up = std::sin(3.0 * kPi / 180.0), out = std::cos(3.0 * kPi / 180.0);
  core::Vec3 round_horizon;
  for (int a = 0; a < kAzimuths; ++a) {
    const double phi = (a + 0.5) / kAzimuths * 2.0 * kPi;
    round_horizon += sky({out * std::cos(phi), out * std::sin(phi), up});
  }
  horizon_ = round_horizon * (1.0 / kAzimuths);
  zenith_ = sky({0.0, 0.0, 1.0});
  // the eye's chromatic adaptation: the daylight of a sun 60° up is white (the clear sky's, worked out once)
  static const core::Vec3 clear_white = white_daylight(kClearSkyTurbidity);
  const core::Vec3 white = turbidity == kClearSkyTurbidity ? clear_white : white_daylight(turbidity);
  const double white_luminance = luminance(white);
  const auto balanced = [&](const core::Vec3& e) {
    return core::Vec3{e.x / white.x, e.y / white.y, e.z / white.z} * white_luminance;
  };
  const Illuminance now = illuminance(sky_, to_sun, turbidity);
  // ambient: a surface facing up sees the sky, one standing sees half of it and half the paving lit by sun
  // and sky; the mean of the two
  const double sun_up = std::max(to_sun.z, 0.0);
  const core::Vec3 sky_illuminance =
      balanced(now.sky * 0.75 + (now.sun * sun_up + now.sky) * (0.25 * kGroundAlbedo));
  const core::Vec3 sun_illuminance = balanced(now.sun);
  sun_lx_ = luminance(sun_illuminance);
  sky_lx_ = luminance(balanced(now.sky));
  // the fixed pipeline adds ambient and diffuse in display units: each end right (in shade, the sky alone;
  // facing the sun, sun and sky), the part-lit between them blended
  const double scale = kSceneKey / adapted_;
  const core::Vec3 shade = encode(sky_illuminance * scale);
  const core::Vec3 lit = encode((sky_illuminance + sun_illuminance) * scale);
  sky_light_ = {std::max(shade.x, kNightAmbient), std::max(shade.y, kNightAmbient),
                std::max(shade.z, kNightAmbient * 1.1)};
  sun_light_ = {std::max(lit.x - shade.x, 0.0), std::max(lit.y - shade.y, 0.0),
                std::max(lit.z - shade.z, 0.0)};
}

core::Vec3 Daylight::display(const core::Vec3& radiance) const {
  const double y = luminance(radiance);
  if (y <= 0.0) return {};
  const double shown = 1.0 - std::exp(-kSkyKey * y / adapted_);
  const core::Vec3 c = encode(radiance * (shown / y));
  return {std::min(c.x, 1.0), std::min(c.y, 1.0), std::min(c.z, 1.0)};
}

core::Vec3 Daylight::sky(const core::Vec3& d) const {
  return display(sky_.radiance(d));
}

}  // namespace harbour::ig
