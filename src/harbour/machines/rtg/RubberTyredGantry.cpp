#include "harbour/machines/rtg/RubberTyredGantry.h"

#include "harbour/machines/parts/DriveReadings.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

constexpr double kG = core::kStandardGravity;
constexpr double kHalfPi = 0.5 * std::numbers::pi;
constexpr double kSpeedFollow_s = 0.25;   // the travel controller's proportional time constant
constexpr double kSpeedIntegral_s = 1.0;  // ... and its integral's
constexpr double kStandstill_mps = 0.02;  // slower than this the crane stands (the turn may start)
constexpr double kBrakesSet_mps = 0.005;  // the holding brakes set once the wheels roll slower than this

// the eight tyres: two to each corner bogie, (x, y) on the frame
std::array<std::pair<double, double>, 8> tyre_positions(const RtgSettings& s) {
  std::array<std::pair<double, double>, 8> at{};
  std::size_t n = 0;
  for (const double side : {-1.0, 1.0})
    for (const double end : {-1.0, 1.0})
      for (const double tyre : {-1.0, 1.0})
        at[n++] = {0.5 * side * s.span_m, 0.5 * end * s.wheelbase_m + 0.5 * tyre * s.bogie_tyre_spacing_m};
  return at;
}

}  // namespace

RtgControlSlots::RtgControlSlots(const scene::ControlTable& t)
    : gantry(t.slot("gantry", scene::ControlKind::kAxis)),
      trolley(t.slot("trolley", scene::ControlKind::kAxis)),
      hoist(t.slot("hoist", scene::ControlKind::kAxis)),
      steer(t.slot("steer", scene::ControlKind::kAxis)),
      wheel_turn(t.slot("wheel_turn", scene::ControlKind::kSwitch)),
      lock(t.slot("lock", scene::ControlKind::kButton)),
      unlock(t.slot("unlock", scene::ControlKind::kButton)),
      emergency_stop(t.slot("emergency_stop", scene::ControlKind::kButton)),
      horn(t.slot("horn", scene::ControlKind::kButton)),
      spreader_20(t.slot("spreader_20", scene::ControlKind::kButton)),
      spreader_40(t.slot("spreader_40", scene::ControlKind::kButton)),
      spreader_45(t.slot("spreader_45", scene::ControlKind::kButton)) {}

RubberTyredGantry::RubberTyredGantry(physics::PhysicsWorld& world, const RtgSettings& s,
                                     const RtgStart& start)
    : world_(world),
      settings_(s),
      slots_(s.controls),
      start_(start),
      yard_(start.position_m.z),
      trolley_start_x_(start.trolley_x_m),
      gantry_(s.gantry_drive),
      trolley_drive_(s.trolley_drive) {
  const core::Mat3 heading = core::Mat3::rotation({0, 0, 1}, start.heading_rad);
  const double total_kg = s.frame_mass_kg + s.trolley_mass_kg + s.rig.spreader.mass_kg;
  const double sag = total_kg * kG / (8.0 * s.tyre.vertical_stiffness_n_per_m);  // it starts settled
  const core::Vec3 centre = start.position_m + core::Vec3{0, 0, s.frame_centre_height_m - sag};
  const auto on_frame = [&](const core::Vec3& local) { return centre + heading * local; };

  // the frame: its mass as a block the size of the gantry; it touches the world by its sills and legs
  physics::BoxSettings frame;
  frame.mass_kg = s.frame_mass_kg;
  frame.half_extents_m = {0.5 * s.span_m, 0.5 * s.wheelbase_m + 1.0, s.frame_centre_height_m};
  frame.pose = {heading, centre};
  frame.collides = false;
  frame_ = world.add_box(frame);
  const double sill_top = s.sill_height_m + 1.2, leg_top = s.trolley_rail_height_m - 1.0;
  for (const double side : {-1.0, 1.0}) {
    const double x = 0.5 * side * s.span_m;
    const double sill_z = 0.5 * (s.sill_height_m + sill_top) - s.frame_centre_height_m;
    world.add_box_shape(frame_,
                        {0.5 * s.leg_width_m, 0.5 * (s.wheelbase_m + s.bogie_tyre_spacing_m) + 0.8,
                         0.5 * (sill_top - s.sill_height_m)},
                        {core::Mat3::identity(), {x, 0.0, sill_z}}, scene::kSurfaceVehicle);
    for (const double end : {-1.0, 1.0})
      world.add_box_shape(
          frame_, {0.5 * s.leg_width_m, 0.6, 0.5 * (leg_top - sill_top)},
          {core::Mat3::identity(),
           {x, 0.5 * end * s.wheelbase_m, 0.5 * (sill_top + leg_top) - s.frame_centre_height_m}},
          scene::kSurfaceVehicle);
  }

  physics::BoxSettings trolley;
  trolley.mass_kg = s.trolley_mass_kg;
  trolley.half_extents_m = {2.5, 3.0, 1.0};
  trolley.pose = {heading,
                  on_frame({start.trolley_x_m, 0.0, s.trolley_rail_height_m - s.frame_centre_height_m})};
  trolley.collides = false;
  trolley_ = world.add_box(trolley);
  trolley_slider_ = world.add_slider(frame_, trolley_, heading.column(0));

  const core::Vec3 spreader_at = on_frame({start.trolley_x_m, 0.0, 0.0});
  rig_ = std::make_unique<SpreaderHoist>(
      world, s.rig, std::vector<physics::BodyId>{trolley_},
      core::Pose{heading, {spreader_at.x, spreader_at.y, start.position_m.z + start.spreader_z_m}});
  wind_areas_[0] = {rig_->spreader_body(), rig_->spreader().half_extents_m(), true};
  // the structure as a box of its height whose faces have its areas
  const double half_height = 0.5 * s.trolley_rail_height_m;
  wind_areas_[1] = {
      frame_,
      {0.25 * s.wind_area_along_m2 / half_height, 0.25 * s.wind_area_across_m2 / half_height, half_height}};
}

double RubberTyredGantry::steer_angle_rad(double steer) const {
  return std::clamp(steer, -1.0, 1.0) * settings_.max_steer_rad + start_.steer_bias_rad;
}

double RubberTyredGantry::tyre_heading_rad(double y_m, double steer) const {
  // in travel the tyres roll along the frame's y; the bogies at +y steer one way and those at -y the other,
  // so the frame turns about its middle (steering only with the wheels in travel)
  const double along = kHalfPi * (1.0 - wheel_turn_);
  if (wheel_turn_ > 0.0) return along;
  const double delta = steer_angle_rad(steer);
  return along + (y_m > 0.0 ? delta : -delta);
}

double RubberTyredGantry::travel_speed_mps() const {
  const core::Pose frame = world_.pose(frame_);
  const core::Vec3 way = frame.rotation.column(wheel_turn_ < 0.5 ? 1 : 0);
  return dot(world_.linear_velocity(frame_), way);
}

double RubberTyredGantry::lane_offset_m() const {
  const core::Vec3 across = core::Mat3::rotation({0, 0, 1}, start_.heading_rad).column(0);
  return dot(world_.pose(frame_).position - start_.position_m, across);
}

double RubberTyredGantry::steer_lever(double yaw_rate_radps) const {
  // the bogies' angle for ω = 2 v tan δ / b at the drive's speed now (the auto-steer's bias unknown)
  const double v = gantry_.reference_mps();
  if (std::abs(v) < kStandstill_mps || wheel_turn_ != 0.0) return 0.0;
  const double delta = std::atan(yaw_rate_radps * settings_.wheelbase_m / (2.0 * v));
  return std::clamp(delta / settings_.max_steer_rad, -1.0, 1.0);
}

double RubberTyredGantry::yaw_rad() const {
  const core::Vec3 x = world_.pose(frame_).rotation.column(0);
  return std::remainder(std::atan2(x.y, x.x) - start_.heading_rad, 2.0 * std::numbers::pi);
}

core::Vec3 RubberTyredGantry::plumb_m() const {
  const core::Pose trolley = world_.pose(trolley_);
  return {trolley.position.x, trolley.position.y, 0.0};
}

// the cab's frame in the trolley's: turned a quarter turn, its x (the way the operator faces) along the
// trolley's +y, towards the spreader hanging beside it
core::Pose RubberTyredGantry::cab_pose() const {
  const core::Pose trolley = world_.pose(trolley_);
  return {trolley.rotation * core::Mat3::rotation({0, 0, 1}, kHalfPi),
          trolley.to_parent(settings_.cab_position_m)};
}

core::Vec3 RubberTyredGantry::eye_on_cab_body_m() const {
  return settings_.cab_position_m + core::Mat3::rotation({0, 0, 1}, kHalfPi) * settings_.eye_m;
}

void RubberTyredGantry::step(const scene::Controls& raw, std::span<const ContainerRef> containers,
                             double dt_s) {
  const scene::Controls c = settings_.controls.in_range(raw);
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  const bool stop = at(slots_.emergency_stop) != 0.0;
  horn_ = at(slots_.horn) != 0.0;

  // the wheels' turn: asked by the switch, started only at a standstill with the travel lever at rest;
  // travel waits until the wheels stand square one way or the other
  const double speed = travel_speed_mps();
  const double wanted_turn = std::round(at(slots_.wheel_turn)) >= 1.0 ? 1.0 : 0.0;
  const bool turning = wheel_turn_ != 0.0 && wheel_turn_ != 1.0;
  const bool standing = std::abs(speed) < kStandstill_mps && gantry_.reference_mps() == 0.0;
  if (wanted_turn != wheel_turn_ && !turning && !standing) {
    if (!turn_refused_) ++turn_refusals_;
    turn_refused_ = true;
  } else if (wanted_turn == wheel_turn_) {
    turn_refused_ = false;
  }
  if (wanted_turn != wheel_turn_ && !turn_refused_ && !stop) {
    const double step = dt_s / settings_.wheel_turn_time_s;
    wheel_turn_ =
        wanted_turn > wheel_turn_ ? std::min(1.0, wheel_turn_ + step) : std::max(0.0, wheel_turn_ - step);
  }
  const bool square = wheel_turn_ == 0.0 || wheel_turn_ == 1.0;

  // gantry travel: the drive's speed reference (slower with a box on), followed on each side of the frame
  // by its own PI speed controller whose force that side's four tyres share; the sides' references follow
  // the steering's turn (an electronic differential: ω = 2 v tan δ / b about the frame's middle)
  const double top_share = gantry_max_speed_mps() / settings_.gantry_drive.max_speed_mps;
  const double lever = square ? std::clamp(at(slots_.gantry), -1.0, 1.0) * top_share : 0.0;
  const DriveOutput g = gantry_.step(lever, 0.0, dt_s, stop);
  const bool across = wheel_turn_ == 1.0;  // travelling along the frame's x
  const core::Pose frame = world_.pose(frame_);
  const core::Vec3 way = frame.rotation.column(across ? 0 : 1);
  const double half_width = across ? 0.5 * settings_.wheelbase_m : 0.5 * settings_.span_m;
  const double steer = at(slots_.steer);
  const double yaw_rate =
      across ? 0.0 : 2.0 * g.velocity_mps * std::tan(steer_angle_rad(steer)) / settings_.wheelbase_m;
  const double mass = settings_.frame_mass_kg + settings_.trolley_mass_kg + settings_.rig.spreader.mass_kg;
  const double gain = 0.5 * mass / kSpeedFollow_s, force_limit = 0.5 * settings_.gantry_drive.max_force_n;
  std::array<double, 2> force{};
  for (std::size_t side = 0; side < 2; ++side) {
    const double offset = side == 0 ? -half_width : half_width;
    const core::Vec3 centre = across ? core::Vec3{0.0, offset, 0.0} : core::Vec3{offset, 0.0, 0.0};
    const double side_speed = dot(world_.point_velocity(frame_, centre), way);
    // + yaw (to the left) drives the +x side faster going along +y
    const double error = g.velocity_mps + yaw_rate * (across ? -offset : offset) - side_speed;
    force[side] = gain * (error + travel_integral_[side] / kSpeedIntegral_s);
    if (std::abs(force[side]) < force_limit)
      travel_integral_[side] += error * dt_s;  // no wind-up at the limit
    force[side] = std::clamp(force[side], -force_limit, force_limit);
  }
  // the holding brakes set once the drive's reference is at rest and the crane has stopped, and stay set
  // until the lever moves it again (a gust beyond them makes them slip: the drive does not take over)
  const double rolling_mps =
      dot(world_.point_velocity(frame_, {0.0, 0.0, -settings_.frame_centre_height_m}), way);
  gantry_braked_ = g.brake && (gantry_braked_ || std::abs(rolling_mps) < kBrakesSet_mps);
  const bool hold = gantry_braked_ || !square || stop;
  if (hold) travel_integral_ = {}, force = {};
  gantry_force_n_ = force[0] + force[1];
  const double brake = hold ? settings_.gantry_drive.brake_force_n / 8.0 * settings_.tyre.radius_m : 0.0;
  gantry_power_w_ = 0.0;
  for (const auto& [x, y] : tyre_positions(settings_)) {
    TyreCommand tyre;
    tyre.steer_rad = tyre_heading_rad(y, steer);
    tyre.drive_torque_nm = force[(across ? y : x) > 0.0 ? 1 : 0] / 4.0 * settings_.tyre.radius_m;
    tyre.brake_torque_nm = brake;
    gantry_power_w_ +=
        apply_tyre(world_, frame_, {x, y, settings_.tyre.radius_m - settings_.frame_centre_height_m},
                   settings_.tyre, tyre, *ground_)
            .drive_power_w;
  }

  // the trolley across the frame, and the spreader on its ropes
  const DriveOutput t = trolley_drive_.step(at(slots_.trolley), trolley_position_m(), dt_s, stop);
  world_.set_slider_motor(trolley_slider_, t.velocity_mps, t.max_force_n);
  SpreaderHoistCommand hoist;
  hoist.hoist = at(slots_.hoist);
  hoist.lock = at(slots_.lock) != 0.0;
  hoist.unlock = at(slots_.unlock) != 0.0;
  hoist.emergency_stop = stop;
  hoist.spreader_size_ft = at(slots_.spreader_20) != 0.0   ? 20
                           : at(slots_.spreader_40) != 0.0 ? 40
                           : at(slots_.spreader_45) != 0.0 ? 45
                                                           : 0;
  rig_->step(hoist, containers, dt_s);
  wind_areas_[0].half_extents_m = rig_->spreader().half_extents_m();
}

double RubberTyredGantry::gantry_max_speed_mps() const {
  return held_item() ? std::min(settings_.gantry_loaded_speed_mps, settings_.gantry_drive.max_speed_mps)
                     : settings_.gantry_drive.max_speed_mps;
}

scene::Controls RubberTyredGantry::crane_controls(const GantryLevers& in) const {
  scene::Controls c = settings_.controls.neutral();
  const auto set = [&](int slot, double v) { c.value[static_cast<std::size_t>(slot)] = v; };
  set(slots_.gantry, in.gantry);
  set(slots_.trolley, in.trolley);
  set(slots_.steer, in.steer);
  set(slots_.hoist, in.hoist);
  set(slots_.lock, in.lock);
  set(slots_.unlock, in.unlock);
  set(slots_.emergency_stop, in.emergency_stop);
  set(slots_.horn, in.horn);
  set(slots_.spreader_20, in.spreader_size_ft == 20);
  set(slots_.spreader_40, in.spreader_size_ft == 40);
  set(slots_.spreader_45, in.spreader_size_ft == 45);
  return c;
}

namespace {
// the indicators an RTG publishes, in snapshot order
constexpr const char* kRtgIndicators[] = {
    "gantry_mps",       "trolley_x_m", "wheel_turn_deg",   "lane_offset_m", "spreader_size_ft",
    "lamp_landed",      "lamp_locked", "lamp_unlocked",    "horn",          "load_t",
    "lamp_brake_fault", "net_load_t",  "spreader_length_m"};
}  // namespace

void RubberTyredGantry::describe(scene::SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"frame", "rtg.frame", {}});
  d.entities.push_back({"trolley", "rtg.trolley", {}});
  d.entities.push_back({"spreader", "rtg.spreader", rig_->spreader().half_extents_m()});
  d.indicators.assign(std::begin(kRtgIndicators), std::end(kRtgIndicators));
  d.drives = {"gantry", "trolley", "hoist", "engine"};
  d.rope_count = std::min(rig_->hoist().rope_count(), scene::kMaxRopes);
}

int RubberTyredGantry::publish(scene::Snapshot& s, int first) const {
  int n = first;
  for (const core::Pose& pose : {world_.pose(frame_), world_.pose(trolley_), spreader_pose()})
    if (n < scene::kMaxEntities) {
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), 0, pose};
      ++n;
    }
  publish_ropes(rig_->hoist(), s);
  const SpreaderState spreader = rig_->spreader_state();
  const TwistlockLamps lamps = rig_->locks().twistlocks().lamps();
  const double values[] = {travel_speed_mps(),
                           trolley_position_m(),
                           90.0 * wheel_turn_,
                           lane_offset_m(),
                           size_ft(spreader.size),
                           lamps.landed ? 1.0 : 0.0,
                           lamps.locked ? 1.0 : 0.0,
                           lamps.unlocked ? 1.0 : 0.0,
                           horn_ ? 1.0 : 0.0,
                           rig_->hoisted_load_n() / kG / 1000.0,
                           rig_->brake_fault() ? 1.0 : 0.0,
                           rig_->net_load_t(),
                           spreader.length_m};
  static_assert(std::size(values) == std::size(kRtgIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  // its drives and the diesel generator set that powers them
  const scene::Snapshot::Drive motors[] = {
      drive_reading(gantry_, gantry_force_n_),
      drive_reading(trolley_drive_, world_.slider_force(trolley_slider_)), drum_reading(rig_->hoist(), 0)};
  const double rated[] = {rated_power_w(settings_.gantry_drive), rated_power_w(settings_.trolley_drive),
                          rated_power_w(rig_->hoist().drum_settings(0))};
  const scene::Snapshot::Drive drives[] = {motors[0], motors[1], motors[2], generator_reading(motors, rated)};
  publish_drives(drives, s);
  return n - first;
}

MachineTally RubberTyredGantry::tally() const {
  MachineTally t;
  const core::Vec3 s = spreader_pose().position, plumb = plumb_m();
  t.swing_m = {s.x - plumb.x, s.y - plumb.y, 0.0};
  t.axes[0] = {"gantry", gantry_.reference_mps()};
  t.axes[1] = {"trolley", trolley_drive_.reference_mps()};
  t.axes[2] = {"hoist", rig_->hoist().drum_rope_speed(0)};
  t.limit_hits = trolley_drive_.limit_hits() + rig_->limit_hits();
  t.hoist_power_w = std::max(0.0, rig_->hoist().drum_power_w(0));
  // the trolley's drive (its slider's motor force times the trolley's speed on the frame) and the gantry's
  // wheel motors (their drive forces at the tyres' contacts times the contacts' speeds)
  t.travel_power_w =
      std::max(0.0, world_.slider_force(trolley_slider_) * world_.slider_rate(trolley_slider_)) +
      std::max(0.0, gantry_power_w_);
  t.warns_before_travel = true;
  t.travelling = gantry_.reference_mps() != 0.0;
  t.travel_position_m = gantry_y_m();
  return t;
}

Telemetry RubberTyredGantry::telemetry() const {
  const MachineTally t = tally();
  return {core::length(t.swing_m),
          rig_->hoist().highest_tension_n(),
          {t.axes[0], t.axes[1], AxisSpeed{"hoist", rig_->hoisting_speed_mps()}}};
}

void RubberTyredGantry::drain_events(StepEvents& events) {
  rig_->locks().twistlocks().drain_events(events.twistlocks);
  rig_->hoist().drain_events(events.ropes);
}

void RubberTyredGantry::inject_fault(MachineFault fault, int detail) {
  if (fault == MachineFault::kHoistBrake) rig_->inject_brake_fault();
  if (fault == MachineFault::kLandedSensor) rig_->inject_landed_sensor_fault(detail);
}

void RubberTyredGantry::hash_into(core::StateHash& hash) const {
  rig_->hoist().hash_into(hash);
  hash.add(gantry_.reference_mps());
  hash.add(trolley_drive_.reference_mps());
  hash.add(travel_integral_);
  hash.add(gantry_braked_);
  hash.add(wheel_turn_);
  hash.add(rig_->locks().twistlocks().lamps());
  hash.add(rig_->spreader_state().length_m);
}

template <typename Self, typename Archive>
void RubberTyredGantry::archive(Self& self, Archive& ar) {
  ar.section(0x52544732, "rtg");  // "RTG2": and the gantry's holding brakes
  ar.part(self.gantry_);
  ar.part(self.trolley_drive_);
  ar(self.travel_integral_, self.gantry_braked_, self.wheel_turn_, self.turn_refused_, self.turn_refusals_,
     self.horn_);
  ar.part(*self.rig_);
}

void RubberTyredGantry::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void RubberTyredGantry::restore_state(core::StateReader& in) {
  archive(*this, in);
  wind_areas_[0].half_extents_m = rig_->spreader().half_extents_m();
}

}  // namespace harbour::sim
