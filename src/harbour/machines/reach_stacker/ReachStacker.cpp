#include "harbour/machines/reach_stacker/ReachStacker.h"

#include "harbour/machines/parts/DriveReadings.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

constexpr double kG = core::kStandardGravity;
constexpr const char* kIndicators[] = {"speed_kmh",        "boom_angle_deg",
                                       "extension_m",      "reach_m",
                                       "rotation_deg",     "side_shift_m",
                                       "load_t",           "capacity_t",
                                       "utilisation",      "limiter_warn",
                                       "limiter_stop",     "lamp_landed",
                                       "lamp_locked",      "horn",
                                       "reversing",        "lamp_parking_brake",
                                       "steering",         "lamp_limiter_fault",
                                       "spreader_length_m"};
// the rotator between the head pin and the spreader: a link hanging on the pin (its centre kLinkDrop_m below
// it) and the turning frame the spreader shifts on (its centre kSlewDrop_m below), half its mass each
constexpr double kLinkDrop_m = 0.3, kSlewDrop_m = 0.75;
const core::Vec3 kLinkHalf_m{0.3, 0.3, 0.3}, kSlewHalf_m{0.3, 1.0, 0.1};

physics::BodyId add_body(physics::PhysicsWorld& world, double mass_kg, const core::Vec3& half_extents_m,
                         const core::Pose& pose, bool collides, int surface) {
  physics::BoxSettings box;
  box.mass_kg = mass_kg;
  box.half_extents_m = half_extents_m;
  box.pose = pose;
  box.collides = collides;
  box.surface = surface;
  return world.add_box(box);
}

// The boom's sections as boxes about their centres: the outer one and the inner one inside it.
core::Vec3 outer_half_extents(const ReachStackerSettings& s) {
  return {s.boom_length_m / 2, 0.45, 0.55};
}
core::Vec3 inner_half_extents(const ReachStackerSettings& s) {
  return {s.boom_length_m / 2, 0.35, 0.42};
}

// Moves a drive's speed and force limit onto a joint's motor.
void drive_hinge(physics::PhysicsWorld& world, physics::HingeId hinge, const DriveOutput& out) {
  world.set_hinge_motor(hinge, out.velocity_mps, out.max_force_n);
}
void drive_slider(physics::PhysicsWorld& world, physics::SliderId slider, const DriveOutput& out) {
  world.set_slider_motor(slider, out.velocity_mps, out.max_force_n);
}

}  // namespace

// Where the bodies stand at the start: the chassis settled on its tyres under the boom's and spreader's
// weights (the small-angle statics), the boom at its angle on it, the rotator and spreader hanging plumb
// under the head pin, square to the boom.
ReachStacker::StartPoses ReachStacker::start_poses(const ReachStackerSettings& s,
                                                   const ReachStackerStart& start) {
  const double boom_reach = s.boom_length_m + start.extension_m;
  const core::Vec3 head_on_chassis =
      s.boom_pivot_m + core::Vec3{std::cos(start.boom_rad), 0.0, std::sin(start.boom_rad)} * boom_reach;
  std::vector<SupportSpring> springs = tyre_springs(s.chassis);
  for (std::size_t n = 0; n < springs.size(); ++n)
    springs[n].base_drop_m = s.chassis.axles[n].hub_z_m - s.chassis.axles.front().hub_z_m;
  const Settling settled = settle(springs, s.mass_kg * kG,
                                  {{(s.boom_pivot_m.x + head_on_chassis.x) / 2, s.boom_mass_kg * kG},
                                   {head_on_chassis.x, s.spreader_mass_kg * kG}});
  const core::Mat3 heading = core::Mat3::rotation({0, 0, 1}, start.heading_rad);
  StartPoses p;
  p.chassis = {
      heading * core::Mat3::rotation({0, 1, 0}, settled.pitch_rad),
      {start.position_m.x, start.position_m.y,
       start.position_m.z + s.chassis.tyre.radius_m - s.chassis.axles.front().hub_z_m - settled.sag_m}};
  const core::Mat3 boom = p.chassis.rotation * core::Mat3::rotation({0, 1, 0}, -start.boom_rad);
  p.pivot = p.chassis.to_parent(s.boom_pivot_m);
  p.head = p.chassis.to_parent(head_on_chassis);
  p.outer = {boom, p.pivot + boom * core::Vec3{s.boom_length_m / 2, 0, 0}};
  p.inner = {boom, p.pivot + boom * core::Vec3{start.extension_m + s.boom_length_m / 2, 0, 0}};
  p.rotator = {heading, p.head - core::Vec3{0, 0, kLinkDrop_m}};
  p.slew = {heading, p.head - core::Vec3{0, 0, kSlewDrop_m}};
  p.spreader = {heading, p.head - core::Vec3{0, 0, s.head_drop_m}};
  return p;
}

ReachStacker::ReachStacker(physics::PhysicsWorld& world, const ReachStackerSettings& settings,
                           const ReachStackerStart& start)
    : ReachStacker(world, settings, start, start_poses(settings, start)) {}

ReachStacker::ReachStacker(physics::PhysicsWorld& world, const ReachStackerSettings& s,
                           const ReachStackerStart& start, const StartPoses& p)
    : world_(world),
      settings_(s),
      cab_(s.controls, s.steer_rate_per_s),
      boom_slot_(s.controls.slot("boom", scene::ControlKind::kAxis)),
      telescope_slot_(s.controls.slot("telescope", scene::ControlKind::kAxis)),
      rotate_slot_(s.controls.slot("rotate", scene::ControlKind::kAxis)),
      shift_slot_(s.controls.slot("side_shift", scene::ControlKind::kAxis)),
      lock_slot_(s.controls.slot("lock", scene::ControlKind::kButton)),
      unlock_slot_(s.controls.slot("unlock", scene::ControlKind::kButton)),
      size_20_slot_(s.controls.slot("spreader_20", scene::ControlKind::kButton)),
      size_40_slot_(s.controls.slot("spreader_40", scene::ControlKind::kButton)),
      body_(add_body(world, s.mass_kg, s.half_extents_m, p.chassis, true, scene::kSurfaceVehicle)),
      outer_(
          add_body(world, s.boom_mass_kg / 2, outer_half_extents(s), p.outer, true, scene::kSurfaceSpreader)),
      inner_(add_body(world, s.boom_mass_kg / 2, inner_half_extents(s), p.inner, false,
                      scene::kSurfaceSpreader)),
      rotator_(
          add_body(world, rotator_mass_kg(s) / 2, kLinkHalf_m, p.rotator, false, scene::kSurfaceSpreader)),
      slew_(add_body(world, rotator_mass_kg(s) / 2, kSlewHalf_m, p.slew, false, scene::kSurfaceSpreader)),
      spreader_(add_body(world, s.spreader.mass_kg,
                         {0.5 * s.spreader.width_m, 0.5 * s.spreader.length_m[1], 0.5 * s.spreader.height_m},
                         p.spreader, false, scene::kSurfaceSpreader)),
      chassis_(s.chassis, body_),
      start_boom_rad_(start.boom_rad),
      start_extension_m_(start.extension_m),
      luff_(s.luff),
      telescope_(s.telescope),
      rotate_(s.rotate),
      side_shift_(s.side_shift) {
  const core::Mat3& heading = p.rotator.rotation;
  const core::Vec3 across = heading * core::Vec3{0, 1, 0};
  // the lift cylinders turn the boom about its pivot (+ raises: about the chassis's -y)
  luff_hinge_ = world.add_hinge(body_, outer_, p.pivot, p.chassis.rotation * core::Vec3{0, -1, 0});
  telescope_slider_ = world.add_slider(outer_, inner_, p.outer.rotation * core::Vec3{1, 0, 0});
  world.set_slider_limits(telescope_slider_,
                          s.telescope.min_position_m - s.telescope_end_stop_margin_m - start.extension_m,
                          s.telescope.max_position_m + s.telescope_end_stop_margin_m - start.extension_m);
  // the rotator hangs free on the head pin (pitch, damped), turns about the vertical below it, and the
  // spreader shifts along its length on it
  tilt_hinge_ = world.add_hinge(inner_, rotator_, p.head, across * -1.0);
  rotate_hinge_ = world.add_hinge(rotator_, slew_, p.head - core::Vec3{0, 0, 2 * kLinkDrop_m}, {0, 0, 1});
  shift_slider_ = world.add_slider(slew_, spreader_, across);
  // the boom's inner section touches nothing (the spreader and its box hang close under it at the head); the
  // outer one touches what it is lowered onto, but not the chassis it lies on or the spreader
  world.exclude_contacts(body_, outer_);
  world.exclude_contacts(outer_, spreader_);
  frame_ = std::make_unique<Spreader>(world, spreader_, scene::kSurfaceSpreader, scene::kSurfaceFlipper,
                                      s.spreader);
  wind_areas_ = {WindArea{body_, s.half_extents_m}, WindArea{outer_, outer_half_extents(s)},
                 WindArea{spreader_, frame_->half_extents_m(), true}};
}

core::Vec3 ReachStacker::head_m() const {
  return world_.pose(inner_).to_parent({settings_.boom_length_m / 2, 0, 0});
}

double ReachStacker::reach_m() const {
  return world_.pose(body_).to_local(head_m()).x - tipping_axle_x_m(settings_);
}

double ReachStacker::load_moment_share() const {
  return sim::load_moment_share(settings_, std::max(reach_m(), 0.1), std::max(0.0, measured_load_kg_));
}

double ReachStacker::pin_force_n() const {
  return world_.hinge_reaction(tilt_hinge_, head_m()).force.z;
}

double ReachStacker::tilt_rad() const {
  return std::acos(std::clamp(world_.pose(body_).rotation.column(2).z, -1.0, 1.0));
}

double ReachStacker::forward_mps() const {
  return chassis_.road_speed_mps(world_);
}

void ReachStacker::step_limiter(double dt_s) {
  // the load on the head pin (the pin carries the rotator, the spreader and what it holds), low-passed
  // (the joint's force from the world's last step: a keyframe carries it, as the world does not)
  const double pin_kg = (restored_pin_n_ ? *restored_pin_n_ : pin_force_n()) / kG;
  restored_pin_n_.reset();
  const double load_kg = pin_kg - settings_.spreader_mass_kg;
  measured_load_kg_ += (load_kg - measured_load_kg_) * std::min(1.0, dt_s / settings_.load_filter_s);
  const double share = load_moment_share();
  const bool over = share >= 1.0;
  if (over && !limiter_stopping_ && limiter_armed_) ++limiter_trips_, limiter_armed_ = false;
  limiter_stopping_ = over;
  if (share < settings_.warn_from) limiter_armed_ = true;
}

void ReachStacker::step(const scene::Controls& raw, std::span<const ContainerRef> containers, double dt_s) {
  const scene::Controls c = settings_.controls.in_range(raw);
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  // driving
  const ChassisCommand command = cab_.step(c, dt_s);
  const bool stop = cab_.emergency_stop();
  chassis_.step(world_, command, *ground_);

  // the boom: at the chart the limiter holds it from lowering and extending (unless it has failed)
  step_limiter(dt_s);
  const bool hold = limiter_stopping_ && !limiter_fault_;
  const double boom_lever = hold ? std::max(0.0, at(boom_slot_)) : at(boom_slot_);
  const double telescope_lever = hold ? std::min(0.0, at(telescope_slot_)) : at(telescope_slot_);
  drive_hinge(world_, luff_hinge_, luff_.step(boom_lever, boom_angle_rad(), dt_s, stop));
  drive_slider(world_, telescope_slider_, telescope_.step(telescope_lever, extension_m(), dt_s, stop));
  drive_hinge(world_, rotate_hinge_, rotate_.step(at(rotate_slot_), rotation_rad(), dt_s, stop));
  drive_slider(world_, shift_slider_, side_shift_.step(at(shift_slot_), side_shift_m(), dt_s, stop));
  // the tilt dampers on the head pin
  const double tilt_torque = -settings_.tilt_damping_nms_per_rad * world_.hinge_rate(tilt_hinge_);
  const core::Vec3 tilt_axis = world_.pose(inner_).rotation.column(1) * -1.0;
  world_.add_torque(rotator_, tilt_axis * tilt_torque);
  world_.add_torque(inner_, tilt_axis * -tilt_torque);

  // the twistlocks; the load hangs when the head pin carries clearly more than the spreader
  const bool load_suspended = measured_load_kg_ > 0.3 * settings_.spreader_mass_kg;
  locks_.step(world_, spreader_, *frame_, containers, settings_.twistlocks, at(lock_slot_) != 0.0,
              at(unlock_slot_) != 0.0, load_suspended, landed_sensor_fault_, dt_s);
  static const SpreaderSize k20 = SpreaderSize::k20ft, k40 = SpreaderSize::k40ft;
  const SpreaderSize* size = at(size_20_slot_) != 0.0 ? &k20 : at(size_40_slot_) != 0.0 ? &k40 : nullptr;
  const TwistlockLamps lamps = locks_.twistlocks().lamps();
  frame_->step(size, {}, lamps.landed || lamps.locked, dt_s);
  wind_areas_[2].half_extents_m = frame_->half_extents_m();

  // a tip-over: the chassis tilted past the limit (counted once until it stands level again)
  const double tilt = tilt_rad();
  if (tilt > settings_.tip_over_rad && !tipped_) ++tip_overs_;
  tipped_ = tilt > settings_.tip_over_rad || (tipped_ && tilt > 0.2 * settings_.tip_over_rad);
}

double ReachStacker::attachment_bottom_z_m() const {
  return world_.pose(spreader_).position.z - frame_->half_extents_m().z;
}

double ReachStacker::lowering_speed_mps() const {
  // the spreader's velocity less the chassis's at the same point, along the chassis's up
  const core::Pose chassis = world_.pose(body_);
  const core::Vec3 at = world_.pose(spreader_).position;
  const core::Vec3 relative =
      world_.linear_velocity(spreader_) - world_.point_velocity(body_, chassis.to_local(at));
  return -dot(relative, chassis.direction_to_parent({0.0, 0.0, 1.0}));
}

core::Pose ReachStacker::cab_pose() const {
  const core::Pose chassis = world_.pose(body_);
  return {chassis.rotation, chassis.to_parent(settings_.cab_position_m)};
}

MachineTally ReachStacker::tally() const {
  MachineTally t;
  t.limiter_trips = limiter_trips_;
  const core::Vec3 spreader = world_.pose(spreader_).position, head = head_m();
  t.swing_m = {spreader.x - head.x, spreader.y - head.y, 0.0};
  t.axes[0] = {"drive", forward_mps()};
  t.axes[1] = {"boom", luff_.reference_mps() * (settings_.boom_length_m + extension_m())};
  t.axes[2] = {"telescope", telescope_.reference_mps()};
  t.travel_power_w = std::max(0.0, chassis_.drive_power_w());
  t.vehicle = true;
  t.tip_overs = tip_overs_;
  return t;
}

void ReachStacker::inject_fault(MachineFault fault, int detail) {
  if (fault == MachineFault::kLoadMomentLimiter) limiter_fault_ = true;
  if (fault == MachineFault::kLandedSensor) landed_sensor_fault_ = detail;
}

bool ReachStacker::fault_active(MachineFault fault) const {
  return fault == MachineFault::kLoadMomentLimiter ? limiter_fault_
         : fault == MachineFault::kLandedSensor    ? landed_sensor_fault_ >= 0
                                                   : false;
}

void ReachStacker::clear_faults() {
  limiter_fault_ = false;
  landed_sensor_fault_ = -1;
}

void ReachStacker::describe(scene::SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"reach_stacker", "reach_stacker.chassis", settings_.half_extents_m});
  d.entities.push_back({"boom_outer", "reach_stacker.boom", outer_half_extents(settings_)});
  d.entities.push_back({"boom_inner", "reach_stacker.boom", inner_half_extents(settings_)});
  d.entities.push_back({"rotator", "reach_stacker.rotator", kLinkHalf_m});
  d.entities.push_back({"rotator_frame", "reach_stacker.rotator", kSlewHalf_m});
  d.entities.push_back({"spreader", "reach_stacker.spreader", frame_->half_extents_m()});
  d.indicators.assign(std::begin(kIndicators), std::end(kIndicators));
  d.drives = {"engine", "boom", "telescope"};
  d.rope_count = 0;
}

int ReachStacker::publish(scene::Snapshot& s, int first) const {
  int n = first;
  for (const physics::BodyId b : {body_, outer_, inner_, rotator_, slew_, spreader_})
    if (n < scene::kMaxEntities) {
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), 0, world_.pose(b)};
      ++n;
    }
  const double reach = reach_m();
  const double capacity_kg = rated_load_kg(settings_, std::max(reach, 0.1));
  const TwistlockLamps lamps = locks_.twistlocks().lamps();
  const double share = load_moment_share();
  const double values[] = {forward_mps() * 3.6,
                           boom_angle_rad() * 180.0 / std::numbers::pi,
                           extension_m(),
                           reach,
                           rotation_rad() * 180.0 / std::numbers::pi,
                           side_shift_m(),
                           measured_load_kg_ / 1000.0,
                           capacity_kg / 1000.0,
                           share,
                           share >= settings_.warn_from ? 1.0 : 0.0,
                           limiter_stopping_ ? 1.0 : 0.0,
                           lamps.landed ? 1.0 : 0.0,
                           lamps.locked ? 1.0 : 0.0,
                           cab_.horn() ? 1.0 : 0.0,
                           cab_.direction() < 0 ? 1.0 : 0.0,
                           cab_.parking_brake() ? 1.0 : 0.0,
                           cab_.steering(),
                           limiter_fault_ ? 1.0 : 0.0,
                           frame_->state().length_m};
  static_assert(std::size(values) == std::size(kIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  const scene::Snapshot::Drive drives[] = {
      chassis_.engine(), drive_reading(luff_.drive(), world_.hinge_torque(luff_hinge_)),
      drive_reading(telescope_.drive(), world_.slider_force(telescope_slider_))};
  publish_drives(drives, s);
  return n - first;
}

void ReachStacker::hash_into(core::StateHash& hash) const {
  hash.add(cab_.steering());
  hash.add(luff_.reference_mps());
  hash.add(telescope_.reference_mps());
  hash.add(rotate_.reference_mps());
  hash.add(side_shift_.reference_mps());
  hash.add(measured_load_kg_);
  hash.add(locks_.twistlocks().lamps());
  hash.add(frame_->state().length_m);
  hash.add(limiter_trips_);
  hash.add(tip_overs_);
}

template <typename Self, typename Archive>
void ReachStacker::archive(Self& self, Archive& ar) {
  ar.section(0x52535431, "reach stacker");  // "RST1"
  ar.part(self.cab_);
  ar.part(self.luff_);
  ar.part(self.telescope_);
  ar.part(self.rotate_);
  ar.part(self.side_shift_);
  ar.part(*self.frame_);
  ar.part(self.locks_.twistlocks());
  ar.part(self.locks_);
  ar(self.measured_load_kg_, self.limiter_stopping_, self.limiter_armed_, self.limiter_fault_, self.tipped_,
     self.landed_sensor_fault_, self.limiter_trips_, self.tip_overs_);
  double pin_n = 0.0;  // the pin force as measured, which the first step after a restore reads
  if constexpr (!Archive::kRestoring) pin_n = self.pin_force_n();
  ar(pin_n);
  if constexpr (Archive::kRestoring) self.restored_pin_n_ = pin_n;
}

void ReachStacker::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void ReachStacker::restore_state(core::StateReader& in) {
  archive(*this, in);
  wind_areas_[2].half_extents_m = frame_->half_extents_m();
}

}  // namespace harbour::sim
