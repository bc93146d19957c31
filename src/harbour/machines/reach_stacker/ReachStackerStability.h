#pragma once

#include <vector>

#include "harbour/machines/parts/WheeledChassis.h"

namespace harbour::sim {

/// A reach stacker's masses and geometry for its stability (settings, from data/machines/reach_stacker.yaml).
/// Frame: the chassis body's centre of mass (chassis and counterweight, without boom and spreader), x
/// forward, z up; the drive axle at the front, the steered axle at the rear.
struct ReachStackerSettings {
  double mass_kg = 47700.0;  ///< chassis and counterweight
  core::Vec3 half_extents_m{4.0, 2.0, 1.0};
  WheeledChassisSettings chassis;
  double boom_mass_kg = 14000.0;  ///< a uniform boom: its centre of mass halfway from its pivot to its head
  core::Vec3 boom_pivot_m{-1.5, 0.0, 2.0};
  double spreader_mass_kg = 8000.0;                   ///< hanging at the boom's head
  std::vector<double> row_reach_m{2.57, 5.42, 8.27};  ///< the rows' load centres ahead of the front axle [m]
  double rated_limit_kg = 45000.0;                    ///< the structure's rating (the chart's most anywhere)
  double stability_margin = 1.29;                     ///< the tipping load over the rated load at a reach
  double warn_from = 0.9;  ///< the load-moment indicator warns from this share of the rated moment
};

/// The front (drive) axle's x on the chassis: the line the machine tips forward over.
double tipping_axle_x_m(const ReachStackerSettings& s);

/// The load at the boom's head (its centre `reach_m` ahead of the front axle) that balances the machine on
/// its front axle: the chassis's moment about that line against the load's, the spreader's (at the head) and
/// the boom's (halfway from its pivot to the head) [kg]; the rear axle carries nothing then.
double tipping_load_kg(const ReachStackerSettings& s, double reach_m);

/// The load chart: the rated load at a reach, the tipping load over the stability margin, at most the
/// structure's rating [kg].
double rated_load_kg(const ReachStackerSettings& s, double reach_m);

/// The load-moment indicator's reading: the load's share of the rated load at its reach (1: at the chart).
double load_moment_share(const ReachStackerSettings& s, double reach_m, double load_kg);

}  // namespace harbour::sim
