#include "harbour/machines/sts/StsCrane.h"

#include "harbour/machines/parts/DriveReadings.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "harbour/core/Units.h"

#include "harbour/core/Braking.h"

namespace harbour::sim {

StsControlSlots::StsControlSlots(const scene::ControlTable& t)
    : gantry(t.slot("gantry", scene::ControlKind::kAxis)),
      trolley(t.slot("trolley", scene::ControlKind::kAxis)),
      hoist(t.slot("hoist", scene::ControlKind::kAxis)),
      boom(t.slot("boom", scene::ControlKind::kAxis)),
      lock(t.slot("lock", scene::ControlKind::kButton)),
      unlock(t.slot("unlock", scene::ControlKind::kButton)),
      emergency_stop(t.slot("emergency_stop", scene::ControlKind::kButton)),
      horn(t.slot("horn", scene::ControlKind::kButton)),
      spreader_20(t.slot("spreader_20", scene::ControlKind::kButton)),
      spreader_40(t.slot("spreader_40", scene::ControlKind::kButton)),
      spreader_45(t.slot("spreader_45", scene::ControlKind::kButton)),
      flipper{t.slot("flipper_1", scene::ControlKind::kSwitch),
              t.slot("flipper_2", scene::ControlKind::kSwitch),
              t.slot("flipper_3", scene::ControlKind::kSwitch),
              t.slot("flipper_4", scene::ControlKind::kSwitch)} {
  for (const int f : flipper)
    if (t[f].positions.size() != 2)
      throw std::invalid_argument("a flipper switch has two positions: up, down");
  for (const int lever : {gantry, trolley, hoist, boom})
    if (t[lever].min != -1.0 || t[lever].max != 1.0)
      throw std::invalid_argument("the STS levers read -1 to 1 ('" + t[lever].label + "')");
}

StsControls StsControlSlots::read(const scene::Controls& c) const {
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  const auto lever = [&](int slot) {
    return std::isfinite(at(slot)) ? std::clamp(at(slot), -1.0, 1.0) : 0.0;
  };
  const auto pressed = [&](int slot) { return std::isfinite(at(slot)) && at(slot) != 0.0; };
  StsControls s;
  s.gantry = lever(gantry);
  s.trolley = lever(trolley);
  s.hoist = lever(hoist);
  s.boom = lever(boom);
  s.lock = pressed(lock);
  s.unlock = pressed(unlock);
  s.emergency_stop = pressed(emergency_stop);
  s.horn = pressed(horn);
  // one size button at a time selects a size; several at once select none
  const int sizes = pressed(spreader_20) + pressed(spreader_40) + pressed(spreader_45);
  if (sizes == 1) s.spreader_size_ft = pressed(spreader_20) ? 20 : pressed(spreader_40) ? 40 : 45;
  for (std::size_t k = 0; k < 4; ++k)
    s.flipper_down[k] = std::isfinite(at(flipper[k])) && std::round(at(flipper[k])) >= 1.0;
  return s;
}

void StsControlSlots::write(const StsControls& s, scene::Controls& c) const {
  const auto set = [&](int slot, double v) { c.value[static_cast<std::size_t>(slot)] = v; };
  set(gantry, s.gantry);
  set(trolley, s.trolley);
  set(hoist, s.hoist);
  set(boom, s.boom);
  set(lock, s.lock);
  set(unlock, s.unlock);
  set(emergency_stop, s.emergency_stop);
  set(horn, s.horn);
  set(spreader_20, s.spreader_size_ft == 20);
  set(spreader_40, s.spreader_size_ft == 40);
  set(spreader_45, s.spreader_size_ft == 45);
  for (std::size_t k = 0; k < 4; ++k)
    set(flipper[k], s.flipper_down[k] ? 1.0 : 0.0);
}

core::Pose StsCrane::cab_pose() const {
  const core::Pose trolley = world_.pose(trolley_body_);
  return {trolley.rotation, trolley.to_parent(settings_.cab_position_m)};
}

scene::Controls StsCrane::controls(const StsControls& sts) const {
  scene::Controls c = settings_.controls.neutral();
  slots_.write(sts, c);
  return c;
}

scene::Controls StsCrane::crane_controls(const GantryLevers& levers) const {
  StsControls sts;  // on rails: no steering; the boom left where it stands
  sts.gantry = levers.gantry;
  sts.trolley = levers.trolley;
  sts.hoist = levers.hoist;
  sts.lock = levers.lock;
  sts.unlock = levers.unlock;
  sts.emergency_stop = levers.emergency_stop;
  sts.horn = levers.horn;
  sts.spreader_size_ft = levers.spreader_size_ft;
  sts.flipper_down = levers.flipper_down;
  return controls(sts);
}

StsCrane::StsCrane(physics::PhysicsWorld& world, const StsCraneSettings& settings, double gantry_y_m,
                   double trolley_x_m, double spreader_z_m)
    : world_(world),
      settings_(settings),
      slots_(settings.controls),
      gantry_start_y_(gantry_y_m),
      trolley_start_x_(trolley_x_m),
      gantry_(settings.gantry_drive),
      trolley_(settings.trolley_drive),
      boom_(settings.boom.drive) {
  // gantry: the crane's base frame, on the quay rails
  physics::BoxSettings gantry;
  gantry.mass_kg = settings.gantry_mass_kg;
  gantry.half_extents_m = {15, 10, 25};
  gantry.pose.position = {0, gantry_y_m, 0};
  gantry.collides = false;
  gantry_body_ = world.add_box(gantry);
  gantry_slider_ = world.add_slider(physics::kWorld, gantry_body_, {0, 1, 0});

  physics::BoxSettings trolley;
  trolley.mass_kg = settings.trolley_mass_kg;
  trolley.half_extents_m = {3, 4, 1};
  trolley.pose.position = {trolley_x_m, gantry_y_m, settings.trolley_rail_height_m};
  trolley.collides = false;
  trolley_body_ = world.add_box(trolley);
  trolley_slider_ = world.add_slider(gantry_body_, trolley_body_, {1, 0, 0});

  // the spreader hangs from the trolley on the hoist reeving's bodies [gantry, trolley, headblock]
  rig_ = std::make_unique<SpreaderHoist>(
      world, settings.spreader_hoist(), std::vector<physics::BodyId>{gantry_body_, trolley_body_},
      core::Pose{core::Mat3::identity(), {trolley_x_m, gantry_y_m, spreader_z_m}});
  wind_areas_[0] = {rig_->spreader_body(), rig_->spreader().half_extents_m(), true};
}

double StsCrane::attachment_bottom_z_m() const {
  return rig_->attachment_bottom_z_m();
}

void StsCrane::step(const StsControls& c, std::span<const ContainerRef> containers, double dt_s) {
  horn_ = c.horn;
  // the boom luffs only with the trolley parked landside; until it is down again the trolley stays parked
  const BoomSettings& boom = settings_.boom;
  const bool trolley_parked = trolley_position_m() <= boom.trolley_park_x_m + 0.01;
  const DriveOutput b = boom_.step(trolley_parked ? c.boom : 0.0, boom_angle_, dt_s, c.emergency_stop);
  boom_angle_ =
      std::clamp(boom_angle_ + b.velocity_mps * dt_s, boom.drive.min_position_m, boom.drive.max_position_m);
  double trolley_lever = c.trolley;
  if (boom_angle_ > 0.0 || b.velocity_mps != 0.0) {
    const DriveSettings& td = settings_.trolley_drive;
    const double room = std::max(0.0, boom.trolley_park_x_m - trolley_position_m());
    trolley_lever = std::min(
        trolley_lever, core::discrete_braking_speed(room, td.deceleration_mps2, dt_s) / td.max_speed_mps);
  }

  // travel drives onto the slider motors
  const DriveOutput g = gantry_.step(c.gantry, gantry_position_m(), dt_s, c.emergency_stop);
  world_.set_slider_motor(gantry_slider_, g.velocity_mps, g.max_force_n);
  const DriveOutput t = trolley_.step(trolley_lever, trolley_position_m(), dt_s, c.emergency_stop);
  world_.set_slider_motor(trolley_slider_, t.velocity_mps, t.max_force_n);

  rig_->step({c.hoist, c.lock, c.unlock, c.emergency_stop, c.spreader_size_ft, c.flipper_down}, containers,
             dt_s);
  wind_areas_[0].half_extents_m = rig_->spreader().half_extents_m();
}

namespace {
// the indicators an STS publishes, in snapshot order
constexpr const char* kStsIndicators[] = {
    "gantry_y_m", "trolley_x_m", "boom_angle_rad",   "spreader_length_m", "spreader_size_ft", "flipper_1",
    "flipper_2",  "flipper_3",   "flipper_4",        "lamp_landed",       "lamp_locked",      "lamp_unlocked",
    "horn",       "load_t",      "lamp_brake_fault", "net_load_t"};
}  // namespace

MachineTally StsCrane::tally() const {
  MachineTally t;
  const core::Vec3 s = spreader_pose().position;
  t.swing_m = {s.x - trolley_position_m(), s.y - gantry_position_m(), 0.0};
  t.axes = {AxisSpeed{"gantry", gantry_.reference_mps()}, AxisSpeed{"trolley", trolley_.reference_mps()},
            AxisSpeed{"hoist", rig_->hoisting_speed_mps()}};
  t.limit_hits = gantry_.limit_hits() + trolley_.limit_hits() + rig_->limit_hits();
  t.hoist_power_w = std::max(0.0, rig_->hoist().drum_power_w(0));
  t.travel_power_w = std::max(0.0, gantry_power_w()) + std::max(0.0, trolley_power_w());
  t.warns_before_travel = true;
  t.travelling = gantry_.reference_mps() != 0.0;
  t.travel_position_m = gantry_position_m();
  return t;
}

Telemetry StsCrane::telemetry() const {
  const MachineTally t = tally();
  return {core::length(t.swing_m), rig_->hoist().highest_tension_n(), t.axes};
}

void StsCrane::describe(scene::SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"gantry", "sts.gantry", {}});
  d.entities.push_back({"trolley", "sts.trolley", {}});
  d.entities.push_back({"spreader", "sts.spreader", rig_->spreader().half_extents_m()});
  d.indicators.assign(std::begin(kStsIndicators), std::end(kStsIndicators));
  d.drives = {"gantry", "trolley", "hoist", "boom"};
  d.rope_count = std::min(rig_->hoist().rope_count(), scene::kMaxRopes);
}

int StsCrane::publish(scene::Snapshot& s, int first) const {
  int n = first;
  for (const core::Pose& pose : {world_.pose(gantry_body_), world_.pose(trolley_body_), spreader_pose()})
    if (n < scene::kMaxEntities) {
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), 0, pose};
      ++n;
    }
  publish_ropes(rig_->hoist(), s);

  const SpreaderState spreader = spreader_state();
  const TwistlockLamps lamps = rig_->locks().twistlocks().lamps();
  const double values[] = {gantry_position_m(),
                           trolley_position_m(),
                           boom_angle_,
                           spreader.length_m,
                           size_ft(spreader.size),
                           spreader.flippers[0],
                           spreader.flippers[1],
                           spreader.flippers[2],
                           spreader.flippers[3],
                           lamps.landed ? 1.0 : 0.0,
                           lamps.locked ? 1.0 : 0.0,
                           lamps.unlocked ? 1.0 : 0.0,
                           horn_ ? 1.0 : 0.0,
                           hoisted_load_n() / core::kStandardGravity / 1000.0,
                           rig_->brake_fault() ? 1.0 : 0.0,
                           rig_->net_load_t()};
  static_assert(std::size(values) == std::size(kStsIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  // the boom is moved kinematically: its winch heard at half its rating while it moves
  const scene::Snapshot::Drive drives[] = {drive_reading(gantry_, world_.slider_force(gantry_slider_)),
                                           drive_reading(trolley_, world_.slider_force(trolley_slider_)),
                                           drum_reading(rig_->hoist(), 0),
                                           drive_reading(boom_, 0.5 * boom_.settings().max_force_n)};
  publish_drives(drives, s);
  return n - first;
}

void StsCrane::drain_events(StepEvents& events) {
  rig_->locks().twistlocks().drain_events(events.twistlocks);
  rig_->hoist().drain_events(events.ropes);
}

void StsCrane::inject_fault(MachineFault fault, int detail) {
  switch (fault) {
    case MachineFault::kHoistBrake:
      rig_->inject_brake_fault();
      break;
    case MachineFault::kLandedSensor:
      rig_->inject_landed_sensor_fault(detail);
      break;
    case MachineFault::kLoadMomentLimiter:  // it has none
      break;
  }
}

void StsCrane::clear_faults() {
  rig_->clear_faults();
}

bool StsCrane::fault_active(MachineFault fault) const {
  return fault == MachineFault::kHoistBrake     ? rig_->brake_fault()
         : fault == MachineFault::kLandedSensor ? rig_->landed_sensor_fault()
                                                : false;
}

void StsCrane::hash_into(core::StateHash& hash) const {
  rig_->hoist().hash_into(hash);
  hash.add(gantry_.reference_mps());
  hash.add(trolley_.reference_mps());
  hash.add(rig_->locks().twistlocks().lamps());
  hash.add(boom_angle_);
  const SpreaderState spreader = spreader_state();
  hash.add(spreader.length_m);
  hash.add(spreader.flippers);
}

template <typename Self, typename Archive>
void StsCrane::archive(Self& self, Archive& ar) {
  ar.section(0x53545333, "crane");  // "STS3": the third layout (twistlock landings debounced)
  ar.part(self.gantry_);
  ar.part(self.trolley_);
  ar.part(self.boom_);
  ar(self.boom_angle_, self.horn_);
  ar.part(*self.rig_);
}

void StsCrane::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void StsCrane::restore_state(core::StateReader& in) {
  archive(*this, in);
  wind_areas_[0].half_extents_m = rig_->spreader().half_extents_m();
}

}  // namespace harbour::sim
