#include "harbour/machines/tractor/TerminalTractor.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::sim {
namespace {

constexpr const char* kTractorIndicators[] = {"speed_kmh", "gear", "steering", "horn"};
constexpr int kReverse = 0, kNeutral = 1;  // the direction selector's positions: reverse, neutral, forward

physics::BodyId add_chassis(physics::PhysicsWorld& world, const TractorSettings& s,
                            const TractorStart& start) {
  // standing on the tyres' static sag (the rear axle's twins stiffer: the mean is near enough, it settles)
  const AxleSettings& axle = s.chassis.axles.front();
  physics::BoxSettings box;
  box.mass_kg = s.mass_kg;
  box.half_extents_m = s.half_extents_m;
  box.pose = {core::Mat3::rotation({0, 0, 1}, start.heading_rad),
              start.position_m + core::Vec3{0, 0, s.chassis.tyre.radius_m - axle.hub_z_m}};
  return world.add_box(box);
}

}  // namespace

ControlTable tractor_control_table() {
  using K = ControlKind;
  return ControlTable(
      {ControlSpec{"steer", K::kAxis, -1.0, 1.0, {}, 0.0, 0.0, "steering wheel, + turns left"},
       ControlSpec{"throttle", K::kAxis, 0.0, 1.0, {}, 0.0, 0.0, "accelerator pedal"},
       ControlSpec{"brake", K::kAxis, 0.0, 1.0, {}, 0.0, 1.0, "brake pedal"},
       ControlSpec{"direction",
                   K::kSwitch,
                   0.0,
                   2.0,
                   {"reverse", "neutral", "forward"},
                   1.0,
                   1.0,
                   "direction selector"},
       ControlSpec{"emergency_stop", K::kButton, 0.0, 1.0, {}, 0.0, 0.0, "full brakes, no drive"},
       ControlSpec{"horn", K::kButton, 0.0, 1.0, {}, 0.0, 0.0, "horn"}});
}

TerminalTractor::TerminalTractor(physics::PhysicsWorld& world, const TractorSettings& settings,
                                 const TractorStart& start)
    : world_(world),
      settings_(settings),
      steer_slot_(settings.controls.slot("steer", ControlKind::kAxis)),
      throttle_slot_(settings.controls.slot("throttle", ControlKind::kAxis)),
      brake_slot_(settings.controls.slot("brake", ControlKind::kAxis)),
      direction_slot_(settings.controls.slot("direction", ControlKind::kSwitch)),
      stop_slot_(settings.controls.slot("emergency_stop", ControlKind::kButton)),
      horn_slot_(settings.controls.slot("horn", ControlKind::kButton)),
      body_(add_chassis(world, settings, start)),
      chassis_(settings.chassis, body_),
      wind_areas_{WindArea{body_, settings.half_extents_m}, WindArea{}} {
  if (!start.trailer) return;
  // in line behind it, its kingpin on the hitch, standing on its tyres' sag
  const TrailerSettings& t = *start.trailer;
  const core::Pose chassis = world.pose(body_);
  const core::Vec3 hitch = chassis.to_parent(settings.hitch_m);
  physics::BoxSettings box;
  box.mass_kg = t.mass_kg;
  box.half_extents_m = t.half_extents_m;
  box.pose = {chassis.rotation, hitch - chassis.rotation * t.kingpin_m};
  trailer_body_ = world.add_box(box);
  world.attach_pivot(body_, trailer_body_, hitch);
  trailer_wheels_.emplace(t.wheels, trailer_body_);
  trailer_half_extents_m_ = t.half_extents_m;
  wind_areas_[1] = {trailer_body_, t.half_extents_m};
}

double TerminalTractor::hitch_angle_rad() const {
  if (trailer_body_ == physics::kWorld) return 0.0;
  const core::Vec3 a = world_.pose(body_).rotation.column(0),
                   b = world_.pose(trailer_body_).rotation.column(0);
  return std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
}

double TerminalTractor::forward_mps() const {
  return dot(world_.linear_velocity(body_), world_.pose(body_).rotation.column(0));
}

void TerminalTractor::step(const Controls& raw, std::span<const ContainerRef>, double dt_s) {
  const Controls c = settings_.controls.in_range(raw);
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  const bool stop = at(stop_slot_) != 0.0;
  horn_ = at(horn_slot_) != 0.0;
  // hydraulic steering: the wheels follow the steering wheel at the steering's rate
  const double most = settings_.steer_rate_per_s * dt_s;
  steering_ += std::clamp(at(steer_slot_) - steering_, -most, most);
  const int direction = static_cast<int>(std::lround(at(direction_slot_)));
  ChassisCommand command;
  command.steer = steering_;
  command.throttle = stop || direction == kNeutral ? 0.0 : at(throttle_slot_);
  command.reverse = direction == kReverse;
  command.brake = stop ? 1.0 : at(brake_slot_);
  chassis_.step(world_, command, 0.0);
  if (trailer_wheels_) {
    // the trailer's brakes work with the tractor's (air brakes on the coupling)
    trailer_wheels_->step(world_, {0.0, false, command.brake, 0.0}, 0.0);
    const bool folded = std::abs(hitch_angle_rad()) > settings_.jackknife_angle_rad;
    if (folded && !jackknifed_) ++jackknifes_;
    jackknifed_ = folded;
  }
}

double TerminalTractor::attachment_bottom_z_m() const {
  return world_.pose(body_).position.z - settings_.half_extents_m.z;
}

core::Pose TerminalTractor::cab_pose() const {
  const core::Pose chassis = world_.pose(body_);
  return {chassis.rotation, chassis.to_parent(settings_.cab_position_m)};
}

MachineTally TerminalTractor::tally() const {
  // how smoothly it is driven: its speed (harsh braking and starts)
  MachineTally t;
  t.axes[0] = {"drive", forward_mps()};
  return t;
}

void TerminalTractor::describe(SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"tractor", "tractor.chassis", settings_.half_extents_m});
  if (trailer_body_ != physics::kWorld) d.entities.push_back({"trailer", "trailer", trailer_half_extents_m_});
  d.indicators.assign(std::begin(kTractorIndicators), std::end(kTractorIndicators));
  d.rope_count = 0;
}

int TerminalTractor::publish(Snapshot& s, int first) const {
  int n = first;
  for (const physics::BodyId b : {body_, trailer_body_})
    if (b != physics::kWorld && n < kMaxEntities) {
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), 0, world_.pose(b)};
      ++n;
    }
  const double speed = forward_mps();
  const double values[] = {
      speed * 3.6,
      static_cast<double>(drivetrain_wheel_torque_nm(settings_.chassis.drivetrain,
                                                     settings_.chassis.tyre.radius_m, 1.0, speed)
                              .second),
      steering_, horn_ ? 1.0 : 0.0};
  static_assert(std::size(values) == std::size(kTractorIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  return n - first;
}

void TerminalTractor::hash_into(core::StateHash& hash) const {
  hash.add(steering_);
  hash.add(horn_);
  hash.add(jackknifes_);
}

void TerminalTractor::save_state(core::StateWriter& out) const {
  out.section(0x54524331);  // "TRC1"
  out.put(steering_);
  out.put(horn_);
  out.put(jackknifed_);
  out.put(jackknifes_);
}

void TerminalTractor::restore_state(core::StateReader& in) {
  in.section(0x54524331, "terminal tractor");
  in.get(steering_);
  in.get(horn_);
  in.get(jackknifed_);
  in.get(jackknifes_);
}

}  // namespace harbour::sim
