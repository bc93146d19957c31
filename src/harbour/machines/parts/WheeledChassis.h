#pragma once

#include <utility>
#include <vector>

#include "harbour/machines/parts/Tyre.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::sim {

/// One axle of a wheeled machine (settings): where it is on the chassis body (its frame: x forward, z up),
/// whether it steers and whether the drivetrain drives it.
struct AxleSettings {
  double x_m = 0.0;           ///< [m] along the chassis
  double half_track_m = 1.0;  ///< [m] wheels at ±this across
  double hub_z_m = -0.5;      ///< [m] wheel centres' height on the chassis body
  bool steered = false;
  bool driven = false;
  int tyres_per_side = 1;       ///< twin tyres count twice (one force element of twice the stiffnesses)
  bool parking_braked = false;  ///< the parking brake's spring brakes act on this axle's wheels
};

/// An engine and an automatic gearbox (settings): the wheel torque at a throttle and road speed.
struct DrivetrainSettings {
  std::vector<std::pair<double, double>> torque_curve{{800, 500}, {1400, 700}, {2200, 600}};  ///< [rpm, N m]
  std::vector<double> gear_ratios{5.0, 2.5, 1.4, 1.0};
  double final_drive = 6.0;
  double efficiency = 0.85;
  /// A torque converter's torque ratio at stall (1: none): below the curve's first engine speed the engine
  /// holds that speed and the converter multiplies its torque, by this much at a standstill, falling linearly
  /// to 1 at that speed.
  double converter_stall_ratio = 1.0;
};

/// A wheeled machine's chassis as data (settings): its axles, tyres, drivetrain, brakes and steering.
struct WheeledChassisSettings {
  std::vector<AxleSettings> axles;
  TyreSettings tyre;
  DrivetrainSettings drivetrain;
  double brake_torque_per_wheel_nm = 20000.0;  ///< [N m] at full pedal
  /// [N m] the parking brake's spring brakes at each wheel of the axles that have them (parking_braked)
  double parking_brake_torque_per_wheel_nm = 0.0;
  double max_steer_rad = 0.6;  ///< the bicycle angle at full steering (at the steered axle)
};

/// The driver's commands.
struct ChassisCommand {
  double throttle = 0.0;  ///< [0, 1]
  bool reverse = false;   ///< the gear selector in reverse (first gear's ratio backwards)
  double brake = 0.0;     ///< [0, 1]
  double steer = 0.0;     ///< [-1, 1], + turns left
  /// the parking brake set: its spring brakes hold as well as the service brakes
  bool parking_brake = false;
};

/// The wheel torque an engine and an ideal automatic gearbox give at `wheel_speed_mps` (the gear with the
/// most torque whose engine speed stays within the curve; the engine's speed held at the curve's first point
/// when slower, the torque converter multiplying its torque there) [N m at one driven axle's share of 1], and
/// the gear it uses (1-based).
std::pair<double, int> drivetrain_wheel_torque_nm(const DrivetrainSettings& drivetrain, double tyre_radius_m,
                                                  double throttle, double wheel_speed_mps);

/// The engine as its sound hears it (Snapshot::Drive): its speed from idle (0) to the torque curve's last
/// point (1), at the road speed in `gear` (1-based; 0: none fits, first gear's ratio) or idling below it, and
/// its load, the throttle (the share of the torque it can give that it gives).
scene::Snapshot::Drive engine_reading(const DrivetrainSettings& drivetrain, double tyre_radius_m,
                                      double throttle, double wheel_speed_mps, int gear);

/// A rigid body's static settling on vertical springs (its tyres and any supports): how far its centre of
/// mass sags and how far it pitches (+ nose down), the sag at x along it being sag + pitch·x.
struct Settling {
  double sag_m = 0.0;
  double pitch_rad = 0.0;
  double sag_at(double x_m) const { return sag_m + pitch_rad * x_m; }
};

/// A vertical spring under a body at x along it [m], its stiffness [N/m] and how far its base sits below
/// where it touches unloaded [m].
struct SupportSpring {
  double x_m = 0.0;
  double stiffness_n_per_m = 0.0;
  double base_drop_m = 0.0;
};

/// The springs a chassis's tyres make (each axle's two sides and twins together).
std::vector<SupportSpring> tyre_springs(const WheeledChassisSettings& chassis);
/// How a body of `weight_n` with point loads [(x, N), down] settles on `springs` (the small-angle statics of
/// a rigid body on linear springs; it needs springs at two places at least).
Settling settle(const std::vector<SupportSpring>& springs, double weight_n,
                const std::vector<std::pair<double, double>>& loads);

/// A wheeled chassis on one physics body: Ackermann steering about the non-steered axles' centre (front,
/// rear or all-wheel steering alike), an automatic drivetrain shared by the driven wheels, brakes on every
/// wheel, and a tyre at each wheel (the body carried on them over the ground). It keeps no state of its
/// own beyond the body (nothing to save).
class WheeledChassis {
 public:
  WheeledChassis(const WheeledChassisSettings& settings, physics::BodyId body);

  /// Pushes the tyres' forces on the body for the next physics step, its wheels on `ground`.
  void step(physics::PhysicsWorld& world, const ChassisCommand& command, const Ground& ground);

  /// The steering angle of a wheel at (x, y) on the chassis for a steering command [rad] (Ackermann: every
  /// wheel square to the line to the turn's centre on the reference axle's line).
  double wheel_angle_rad(double x_m, double y_m, double steer) const;
  /// The turn's radius at the reference point for a steering command [m] (+ to the left; 0 steering:
  /// infinite).
  double turn_radius_m(double steer) const;
  /// The reference point's x: the centre of the non-steered axles (where the turn's centre lies across).
  double reference_x_m() const { return reference_x_; }
  /// The steering base: the steered axle's distance from the reference point (a bicycle's wheelbase).
  double steer_base_m() const { return steer_base_m_; }
  const WheeledChassisSettings& settings() const { return settings_; }
  /// The speed over the ground along the heading where the wheels touch it, under the reference point
  /// [m/s] (a speedometer's: a tall body rocking on its tyres moves its top, not its wheels).
  double road_speed_mps(const physics::PhysicsWorld& world) const;
  /// The engine in the last step (for its sound).
  scene::Snapshot::Drive engine() const { return engine_; }
  /// [W] what the drive delivered to the wheels' contacts over the last step (their drive forces times the
  /// contacts' speeds along their headings, summed; braking and rolling resistance not counted)
  double drive_power_w() const { return drive_power_w_; }

 private:
  WheeledChassisSettings settings_;
  physics::BodyId body_;
  double reference_x_ = 0.0, steer_base_m_ = 1.0;
  int driven_wheels_ = 0;
  scene::Snapshot::Drive engine_;  // published: not state
  double drive_power_w_ = 0.0;     // measured: not state
};

}  // namespace harbour::sim
