#pragma once

#include <vector>

#include "harbour/machines/parts/Drive.h"
#include "harbour/machines/parts/Spreader.h"
#include "harbour/machines/parts/Twistlocks.h"
#include "harbour/machines/parts/WheeledChassis.h"
#include "harbour/scene/Controls.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::sim {

/// A reach stacker (settings, from data/machines/reach_stacker.yaml): its masses and geometry for its
/// stability, its boom, spreader and drives. Frame: the chassis body's centre of mass (chassis and
/// counterweight, without boom and spreader), x forward, z up; the drive axle at the front, the steered axle
/// at the rear. The boom is two sections of half its mass each, as long as each other, the inner one
/// telescoping out of the outer: their centre of mass lies halfway from the pivot to the head at any
/// extension, as the stability below takes it.
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

  double steer_rate_per_s = 0.8;  ///< steering command travel per second
  double boom_length_m = 9.0;     ///< [m] pivot to head pin, the telescope in
  DriveSettings luff;             ///< the lift cylinders: boom angle [rad] (speeds rad/s, torques N m)
  DriveSettings telescope;        ///< the extension cylinder: extension [m] from in
  /// [m] the telescope's end stops lie this far beyond its drive's travel (its limit switches), so the drive,
  /// braked at a switch, never rests on a stop: ODE puts a motor's whole force on the bodies for a step when
  /// a joint at its stop is driven away from it, and the braked drive's hold did so every 0.86 s
  double telescope_end_stop_margin_m = 0.05;
  SpreaderSettings spreader;  ///< its frame (mass: the frame's; spreader_mass_kg adds the rotator)
  double head_drop_m = 1.3;   ///< [m] head pin to the spreader frame's centre, hanging
  double tilt_damping_nms_per_rad = 3e5;  ///< the spreader's pitch on the head pin (tilt dampers)
  DriveSettings rotate;                   ///< the rotator: rotation [rad] from square to the boom
  DriveSettings side_shift;               ///< [m] along the spreader's length
  TwistlockSettings twistlocks;
  double load_filter_s = 0.5;   ///< [s] the load-moment indicator's low-pass on the head's load
  double tip_over_rad = 0.087;  ///< a tilt of the chassis from level counted as a tip-over (5 deg)
  core::Vec3 cab_position_m{1.5, 0.0, 1.0};  ///< the cab's floor (chassis frame)
  core::Vec3 eye_m{0.0, 0.0, 1.2};
  scene::CabSight sight;
  scene::ControlTable controls;  ///< the cab's controls, by label (its machine file's)
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

/// The rotator's and links' mass between the boom's head and the spreader's frame [kg].
inline double rotator_mass_kg(const ReachStackerSettings& s) {
  return s.spreader_mass_kg - s.spreader.mass_kg;
}

/// The load-moment indicator's reading: the load's share of the rated load at its reach (1: at the chart).
double load_moment_share(const ReachStackerSettings& s, double reach_m, double load_kg);

}  // namespace harbour::sim
