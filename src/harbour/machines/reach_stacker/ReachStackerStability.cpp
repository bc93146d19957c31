#include "harbour/machines/reach_stacker/ReachStackerStability.h"

#include <algorithm>
#include <limits>

namespace harbour::sim {

double tipping_axle_x_m(const ReachStackerSettings& s) {
  double front = -std::numeric_limits<double>::infinity();
  for (const AxleSettings& a : s.chassis.axles)
    front = std::max(front, a.x_m);
  return front;
}

double tipping_load_kg(const ReachStackerSettings& s, double reach_m) {
  // moments about the front axle's line, in kg·m: the chassis behind it against what is ahead of it
  const double front = tipping_axle_x_m(s);
  const double chassis = s.mass_kg * front;  // its centre of mass at x = 0
  const double boom = s.boom_mass_kg * ((s.boom_pivot_m.x - front) + reach_m) / 2.0;
  return (chassis - boom) / reach_m - s.spreader_mass_kg;
}

double rated_load_kg(const ReachStackerSettings& s, double reach_m) {
  return std::clamp(tipping_load_kg(s, reach_m) / s.stability_margin, 0.0, s.rated_limit_kg);
}

double load_moment_share(const ReachStackerSettings& s, double reach_m, double load_kg) {
  const double rated = rated_load_kg(s, reach_m);
  return rated > 0.0 ? load_kg / rated : std::numeric_limits<double>::infinity();
}

}  // namespace harbour::sim
