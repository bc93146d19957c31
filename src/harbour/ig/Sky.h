#pragma once

#include <array>

#include "harbour/core/Vec3.h"

namespace harbour::ig {

/// Turbidity of a clear harbour sky (Preetham's scale: 2 very clear, 3 clear, 6 light haze).
inline constexpr double kClearSkyTurbidity = 2.5;

/// The clear sky of Preetham, Shirley & Smits (1999), "A practical analytic model for daylight": Perez's
/// all-weather distribution F(θ, γ) = (1 + A e^{B / cos θ})(1 + C e^{D γ} + E cos² γ) for the luminance Y and
/// the chromaticities x, y, its five coefficients linear in the turbidity, relative to the zenith's absolute
/// luminance and chromaticity (fitted polynomials in the sun's zenith angle). Below the horizon the sun keeps
/// the distribution it had setting, and twilight dims it by the depression (`twilight_dimming`); the ozone's
/// Chappuis band, on the long paths of a low sun's light, filters what it scatters (the twilight's blue).
class ClearSky {
 public:
  explicit ClearSky(const core::Vec3& to_sun, double turbidity = kClearSkyTurbidity);

  /// CIE xyY of the sky seen in the unit direction `d` (z up; Y in cd/m²); at and below the horizon the
  /// horizon's.
  core::Vec3 xyY(const core::Vec3& d) const;
  /// Linear sRGB in cd/m² (the luminance's units) in the direction `d`, the ozone's absorption included.
  core::Vec3 radiance(const core::Vec3& d) const;
  /// The zenith's luminance, cd/m², twilight's dimming included.
  double zenith_luminance() const { return zenith_.z * twilight_; }
  /// Perez's relative distribution for the luminance: Y(d) / Y(zenith) (below the horizon: the setting
  /// sun's).
  double relative_luminance(const core::Vec3& d) const;

 private:
  using Perez = std::array<double, 5>;
  static double perez(const Perez& c, double cos_theta, double gamma);
  double gamma_to(const core::Vec3& d) const;

  core::Vec3 sun_;        // towards the sun, held at the horizon while it is below
  double sun_theta_ = 0;  // its zenith angle
  double twilight_ = 1;   // the luminance's share left by the sun's depression
  core::Vec3 zenith_;     // x, y, Y (cd/m²) at the zenith before twilight's dimming
  Perez y_lum_{}, x_chroma_{}, y_chroma_{};
  double at_zenith_lum_ = 1, at_zenith_x_ = 1, at_zenith_y_ = 1;  // F(0, θs) of each
  core::Vec3 ozone_;  // the Chappuis band's transmittance per channel
};

/// The zenith's luminance share left at a solar depression `depression_deg` (0 at sunset): 10^(-0.42) a
/// degree through civil and nautical twilight, 10^(-0.23) a degree from 12° to 18° (astronomical twilight),
/// then the night's.
double twilight_dimming(double depression_deg);

/// The sun's direct beam reaching the ground at elevation `elevation` (rad): its transmittance at 680, 550
/// and 440 nm (linear R, G, B) through Rayleigh scattering (τ = 0.008735 λ^-4.08, λ in µm), aerosol
/// (Ångström, β = 0.04608 T - 0.04586 as Preetham, α = 1.3) and ozone (300 DU), along Kasten & Young's (1989)
/// air mass. Zero below the horizon.
core::Vec3 sun_beam_transmittance(double elevation, double turbidity = kClearSkyTurbidity);

/// The relative optical air mass towards a body at elevation `elevation` (rad), after Kasten & Young (1989):
/// 1 / (sin h + 0.50572 (h° + 6.07995)^-1.6364).
double relative_air_mass(double elevation);

/// Linear sRGB (D65) of CIE xyY.
core::Vec3 linear_srgb(const core::Vec3& xyY);

/// What the image generator draws and lights with for a sun: the clear sky's colours as an eye adapted to
/// its brightness sees them (display sRGB, 0-1), the sun's direct light and the sky's diffuse light in the
/// fixed pipeline's units (a white surface facing the noon sun: about 0.85).
class Daylight {
 public:
  explicit Daylight(const core::Vec3& to_sun, double turbidity = kClearSkyTurbidity);

  /// The sky's display colour in the unit direction `d`.
  core::Vec3 sky(const core::Vec3& d) const;
  /// The mean of the sky's display colour round the horizon, 3° up (the colour of distance: fog's).
  const core::Vec3& horizon() const { return horizon_; }
  const core::Vec3& zenith() const { return zenith_; }
  /// The sun's light on a surface facing it (light 0's diffuse colour).
  const core::Vec3& sun_light() const { return sun_light_; }
  /// The sky's and the ground's reflected light on any surface (ambient).
  const core::Vec3& sky_light() const { return sky_light_; }
  /// Illuminance, lux (luminous, white-balanced to the daylight of a sun 60° up): the sun's beam on a surface
  /// facing it, and the sky's on a horizontal surface.
  double sun_illuminance_lx() const { return sun_lx_; }
  double sky_illuminance_lx() const { return sky_lx_; }
  /// The luminance the eye is adapted to, cd/m².
  double adapted_luminance() const { return adapted_; }
  const ClearSky& clear_sky() const { return sky_; }

 private:
  core::Vec3 display(const core::Vec3& radiance) const;

  ClearSky sky_;
  double adapted_ = 1;
  double sun_lx_ = 0, sky_lx_ = 0;
  core::Vec3 horizon_, zenith_, sun_light_, sky_light_;
};

}  // namespace harbour::ig
