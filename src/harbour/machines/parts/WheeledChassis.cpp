#include "harbour/machines/parts/WheeledChassis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace harbour::sim {
namespace {

double engine_torque_nm(const std::vector<std::pair<double, double>>& curve, double rpm) {
  if (rpm <= curve.front().first) return curve.front().second;
  for (std::size_t k = 1; k < curve.size(); ++k)
    if (rpm <= curve[k].first) {
      const double s = (rpm - curve[k - 1].first) / (curve[k].first - curve[k - 1].first);
      return curve[k - 1].second + s * (curve[k].second - curve[k - 1].second);
    }
  return 0.0;  // beyond the governor
}

}  // namespace

std::pair<double, int> drivetrain_wheel_torque_nm(const DrivetrainSettings& d, double tyre_radius_m,
                                                  double throttle, double wheel_speed_mps) {
  double best = 0.0;
  int gear = 0;
  const double wheel_rpm = std::abs(wheel_speed_mps) / tyre_radius_m * 60.0 / (2.0 * std::numbers::pi);
  for (std::size_t g = 0; g < d.gear_ratios.size(); ++g) {
    const double ratio = d.gear_ratios[g] * d.final_drive;
    const double rpm = wheel_rpm * ratio;
    if (rpm > d.torque_curve.back().first) continue;  // this gear would over-speed the engine
    const double idle_rpm = d.torque_curve.front().first;
    const double converter =
        rpm < idle_rpm ? d.converter_stall_ratio - (d.converter_stall_ratio - 1.0) * rpm / idle_rpm : 1.0;
    const double torque = engine_torque_nm(d.torque_curve, rpm) * converter * ratio * d.efficiency;
    if (torque > best) best = torque, gear = static_cast<int>(g) + 1;
  }
  return {std::clamp(throttle, 0.0, 1.0) * best, gear};
}

scene::Snapshot::Drive engine_reading(const DrivetrainSettings& d, double tyre_radius_m, double throttle,
                                      double wheel_speed_mps, int gear) {
  const double idle_rpm = d.torque_curve.front().first, top_rpm = d.torque_curve.back().first;
  const double ratio = gear > 0 ? d.gear_ratios[static_cast<std::size_t>(gear - 1)] * d.final_drive
                                : d.gear_ratios.front() * d.final_drive;
  const double rpm =
      std::max(idle_rpm, std::abs(wheel_speed_mps) / tyre_radius_m * 60.0 / (2.0 * std::numbers::pi) * ratio);
  return {std::clamp((rpm - idle_rpm) / (top_rpm - idle_rpm), 0.0, 1.0), std::clamp(throttle, 0.0, 1.0)};
}

std::vector<SupportSpring> tyre_springs(const WheeledChassisSettings& chassis) {
  std::vector<SupportSpring> springs;
  for (const AxleSettings& a : chassis.axles)
    springs.push_back({a.x_m, 2.0 * a.tyres_per_side * chassis.tyre.vertical_stiffness_n_per_m, 0.0});
  return springs;
}

Settling settle(const std::vector<SupportSpring>& springs, double weight_n,
                const std::vector<std::pair<double, double>>& loads) {
  // heave h and pitch θ: Σ k (h + θx − b) = W + ΣL, Σ k x (h + θx − b) = Σ L x
  double k0 = 0.0, k1 = 0.0, k2 = 0.0, force = weight_n, moment = 0.0;
  for (const SupportSpring& s : springs) {
    k0 += s.stiffness_n_per_m;
    k1 += s.stiffness_n_per_m * s.x_m;
    k2 += s.stiffness_n_per_m * s.x_m * s.x_m;
    force += s.stiffness_n_per_m * s.base_drop_m;
    moment += s.stiffness_n_per_m * s.base_drop_m * s.x_m;
  }
  for (const auto& [x, load] : loads) {
    force += load;
    moment += load * x;
  }
  const double det = k0 * k2 - k1 * k1;
  if (!(std::abs(det) > 1e-9 * k0 * k2)) throw std::invalid_argument("settling needs springs at two places");
  return {(force * k2 - moment * k1) / det, (k0 * moment - k1 * force) / det};
}

WheeledChassis::WheeledChassis(const WheeledChassisSettings& settings, physics::BodyId body)
    : settings_(settings), body_(body) {
  double fixed_x = 0.0;
  int fixed = 0;
  for (const AxleSettings& a : settings.axles) {
    if (!a.steered) fixed_x += a.x_m, ++fixed;
    if (a.driven) driven_wheels_ += 2;
  }
  if (settings.axles.empty()) throw std::invalid_argument("a wheeled chassis needs axles");
  reference_x_ = fixed > 0 ? fixed_x / fixed : 0.0;
  steer_base_m_ = 0.0;
  for (const AxleSettings& a : settings.axles)
    if (a.steered) steer_base_m_ = std::max(steer_base_m_, std::abs(a.x_m - reference_x_));
}

double WheeledChassis::turn_radius_m(double steer) const {
  const double angle = std::clamp(steer, -1.0, 1.0) * settings_.max_steer_rad;
  if (std::abs(angle) < 1e-9 || steer_base_m_ <= 0.0) return std::numeric_limits<double>::infinity();
  return steer_base_m_ / std::tan(angle);
}

double WheeledChassis::wheel_angle_rad(double x_m, double y_m, double steer) const {
  const double r = turn_radius_m(steer);
  if (!std::isfinite(r)) return 0.0;
  return std::atan((x_m - reference_x_) / (r - y_m));
}

double WheeledChassis::road_speed_mps(const physics::PhysicsWorld& world) const {
  const double contact_z = settings_.axles.front().hub_z_m - settings_.tyre.radius_m;
  const core::Vec3 v = world.point_velocity(body_, {reference_x_, 0.0, contact_z});
  return dot(v, world.pose(body_).rotation.column(0));
}

void WheeledChassis::step(physics::PhysicsWorld& world, const ChassisCommand& command, const Ground& ground) {
  const core::Pose pose = world.pose(body_);
  const double forward = dot(world.linear_velocity(body_), pose.rotation.column(0));
  const auto [wheel_torque, gear] =
      drivetrain_wheel_torque_nm(settings_.drivetrain, settings_.tyre.radius_m, command.throttle, forward);
  const double axle_torque = wheel_torque * (command.reverse ? -1.0 : 1.0);
  engine_ = engine_reading(settings_.drivetrain, settings_.tyre.radius_m, command.throttle, forward, gear);
  const double brake = std::clamp(command.brake, 0.0, 1.0) * settings_.brake_torque_per_wheel_nm;
  drive_power_w_ = 0.0;
  for (const AxleSettings& a : settings_.axles) {
    TyreSettings tyre = settings_.tyre;  // twin tyres: one element of twice the stiffnesses
    tyre.vertical_stiffness_n_per_m *= a.tyres_per_side;
    tyre.vertical_damping_ns_per_m *= a.tyres_per_side;
    tyre.cornering_stiffness_n_per_rad *= a.tyres_per_side;
    for (const double side : {1.0, -1.0}) {
      const double y = side * a.half_track_m;
      TyreCommand c;
      c.steer_rad = a.steered ? wheel_angle_rad(a.x_m, y, command.steer) : 0.0;
      c.drive_torque_nm = a.driven && driven_wheels_ > 0 ? axle_torque / driven_wheels_ : 0.0;
      const double parking =
          command.parking_brake && a.parking_braked ? settings_.parking_brake_torque_per_wheel_nm : 0.0;
      c.brake_torque_nm = std::max(brake, parking) * a.tyres_per_side;
      drive_power_w_ += apply_tyre(world, body_, {a.x_m, y, a.hub_z_m}, tyre, c, ground).drive_power_w;
    }
  }
}

}  // namespace harbour::sim
