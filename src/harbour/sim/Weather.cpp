#include "harbour/sim/Weather.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::sim {

Weather::Weather(const WeatherSettings& settings, std::uint64_t seed) : settings_(settings), rng_(seed) {
  gusts_.reserve(32);
}

void Weather::step(double dt_s) {
  time_s_ += dt_s;
  // Ornstein-Uhlenbeck: relaxes with the turbulence time scale, standard deviation I * U
  const double sigma = settings_.turbulence_intensity * settings_.wind_mean_mps;
  if (sigma > 0.0) {
    const double a = std::exp(-dt_s / settings_.turbulence_time_s);
    const double normal =
        std::sqrt(-2.0 * std::log(1.0 - rng_.uniform())) * std::cos(2.0 * std::numbers::pi * rng_.uniform());
    turbulence_ = a * turbulence_ + sigma * std::sqrt(1.0 - a * a) * normal;
  }
  // a gust that is over adds nothing again: drop it, so that the list stays as short as the gusts blowing
  std::erase_if(gusts_, [&](const Gust& g) { return time_s_ - g.start_s > g.duration_s; });
}

double Weather::speed_mps() const {
  double u = settings_.wind_mean_mps + turbulence_;
  for (const Gust& g : gusts_) {
    const double t = time_s_ - g.start_s;
    if (t >= 0.0 && t <= g.duration_s)
      u += 0.5 * g.amplitude_mps * (1.0 - std::cos(2.0 * std::numbers::pi * t / g.duration_s));
  }
  return std::clamp(u, 0.0, kMaxWindSpeed_mps);
}

namespace {
// blowing from `from_rad` (clockwise from north = +y): the air moves the opposite way
core::Vec3 air_velocity(double speed_mps, double from_rad) {
  return {-speed_mps * std::sin(from_rad), -speed_mps * std::cos(from_rad), 0.0};
}
}  // namespace

core::Vec3 Weather::wind() const {
  return air_velocity(speed_mps(), settings_.wind_from_rad);
}

core::Vec3 Weather::mean_wind() const {
  return air_velocity(settings_.wind_mean_mps, settings_.wind_from_rad);
}

double Weather::time_of_day_h() const {
  return std::fmod(settings_.time_of_day_h + time_s_ / 3600.0, 24.0);
}

core::Vec3 box_drag(const core::Vec3& wind, const core::Vec3& body_velocity, const core::Pose& pose,
                    const core::Vec3& half_extents_m, double drag_coefficient, double air_density_kg_m3) {
  core::Vec3 relative = wind - body_velocity;
  relative.z = 0.0;
  const double speed = core::length(relative);
  if (speed <= 0.0) return {};
  // projected area across the flow: the box's x face and y face weighted by the flow's direction in its frame
  const core::Vec3 local = pose.direction_to_local(relative * (1.0 / speed));
  const double area =
      4.0 * half_extents_m.z * (std::abs(local.x) * half_extents_m.y + std::abs(local.y) * half_extents_m.x);
  return relative * (0.5 * air_density_kg_m3 * drag_coefficient * area * speed);
}

void Weather::set_wind(double mean_mps, double from_rad, double turbulence_intensity) {
  settings_.wind_mean_mps = mean_mps;
  settings_.wind_from_rad = from_rad;
  settings_.turbulence_intensity = turbulence_intensity;
}

void Weather::set_time_of_day(double hours) {
  double start = std::fmod(hours - time_s_ / 3600.0, 24.0);  // what the clock would have read at t = 0
  if (start < 0.0) start += 24.0;
  settings_.time_of_day_h = start;
}

template <typename Self, typename Archive>
void Weather::archive(Self& self, Archive& ar) {
  // what the instructor can change (the date and the latitude stay the scenario's). Version 3 adds the cloud
  // cover; a clear sky is still saved as version 2 was, so the states (and the state hashes) of every run
  // recorded before clouds came are the same bytes and their recordings replay as they were
  constexpr std::uint32_t kVersion2 = 0x57545832, kVersion3 = 0x57545833;  // "WTX2", "WTX3"
  auto& s = self.settings_;
  bool clouded = s.cloud_oktas != 0.0;
  if constexpr (Archive::kRestoring) clouded = ar.next_section_is(kVersion3);
  ar.section(clouded ? kVersion3 : kVersion2, "weather");
  ar(s.wind_mean_mps, s.wind_from_rad, s.turbulence_intensity, s.turbulence_time_s, s.visibility_m,
     s.rain_mm_per_h, s.time_of_day_h, s.air_density_kg_m3);
  if (clouded) {
    ar(s.cloud_oktas);
  } else {
    if constexpr (Archive::kRestoring) s.cloud_oktas = 0.0;
  }
  ar(self.rng_, self.time_s_, self.turbulence_, self.gusts_);
}

void Weather::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void Weather::restore_state(core::StateReader& in) {
  archive(*this, in);
}

}  // namespace harbour::sim
