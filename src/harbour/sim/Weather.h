#pragma once

#include "harbour/core/StateArchive.h"

#include <vector>

#include "harbour/core/Rng.h"
#include "harbour/core/Vec3.h"

namespace harbour::sim {

/// Physical bounds of the wind model (docs/reliability.md). Cranes stop work at 20-25 m/s and are stowed
/// against storms; hurricane force (Beaufort 12) begins at 32.7 m/s. Past these the model is not meant to
/// run.
inline constexpr double kMaxMeanWind_mps = 50.0;  ///< [m/s] largest mean wind an exercise or instructor sets
inline constexpr double kMaxGust_mps = 30.0;      ///< [m/s] largest amplitude of one gust
inline constexpr double kOvercast_oktas = 8.0;    ///< cloud cover: the whole sky under cloud
inline constexpr double kMaxWindSpeed_mps =
    70.0;  ///< [m/s] mean, turbulence and gusts together saturate here

/// Weather at the start of an exercise (settings).
struct WeatherSettings {
  double wind_mean_mps = 0.0;         ///< [m/s] 10-minute mean at boom height
  double wind_from_rad = 0.0;         ///< [rad] direction the wind blows from, clockwise from north (y)
  double turbulence_intensity = 0.0;  ///< [-] standard deviation / mean of the turbulent part
  double turbulence_time_s =
      3.0;                        ///< [s] time scale of the turbulence (first-order; EN 13001 uses 3 s gusts)
  double visibility_m = 20000.0;  ///< [m] for the image generator's fog
  double rain_mm_per_h = 0.0;     ///< [mm/h]
  double cloud_oktas = 0.0;       ///< eighths of the sky under cloud (0 clear, 8 overcast)
  double time_of_day_h = 12.0;    ///< [h] local solar time at the start
  double air_density_kg_m3 = 1.225;  ///< [kg/m^3]
  double day_of_year = 80.0;         ///< 1..366, for the sun's declination and the moon (80: March equinox)
  double latitude_deg = 40.0;  ///< [deg] the harbour's, north positive; neither is part of the saved state
};

/// A discrete "1-cosine" gust: u = amplitude (1 - cos(2 pi (t - start) / duration)) / 2 within the gust.
struct Gust {
  double start_s = 0.0;
  double duration_s = 3.0;     ///< [s]
  double amplitude_mps = 0.0;  ///< [m/s] peak added to the mean
  friend bool operator==(const Gust&, const Gust&) = default;
};

/// The wind field (uniform over the crane) and the weather state the image generator shows.
class Weather {
 public:
  Weather(const WeatherSettings& settings, std::uint64_t seed);

  /// Advances the turbulence and the clock by `dt_s`; forgets gusts that are over.
  void step(double dt_s);
  /// Adds a scripted gust.
  void add_gust(const Gust& gust) { gusts_.push_back(gust); }
  /// The instructor changes the weather (part of the saved state from then on).
  void set_wind(double mean_mps, double from_rad, double turbulence_intensity);
  void set_visibility(double metres) { settings_.visibility_m = metres; }
  void set_rain(double mm_per_h) { settings_.rain_mm_per_h = mm_per_h; }
  void set_cloud(double oktas) { settings_.cloud_oktas = oktas; }
  /// The clock jumps to `hours` and runs on from there.
  void set_time_of_day(double hours);
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);
  /// Wind velocity now [m/s], world frame (the air moves towards wind_from + 180 deg).
  core::Vec3 wind() const;
  /// The mean wind alone (no turbulence, no gusts) [m/s], world frame.
  core::Vec3 mean_wind() const;
  /// Wind speed now [m/s], at most kMaxWindSpeed_mps however many gusts overlap.
  double speed_mps() const;
  double time_of_day_h() const;
  const WeatherSettings& settings() const { return settings_; }
  double turbulence_mps() const { return turbulence_; }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  WeatherSettings settings_;
  core::Rng rng_;
  double time_s_ = 0.0;
  double turbulence_ = 0.0;  // [m/s] first-order (Ornstein-Uhlenbeck) process along the mean wind
  std::vector<Gust> gusts_;
};

/// Aerodynamic drag on a box in the wind: F = 1/2 rho Cd A |v_rel| v_rel, with A the box's projected area
/// across the relative wind (horizontal wind only).
core::Vec3 box_drag(const core::Vec3& wind, const core::Vec3& body_velocity, const core::Pose& pose,
                    const core::Vec3& half_extents_m, double drag_coefficient, double air_density_kg_m3);

}  // namespace harbour::sim
