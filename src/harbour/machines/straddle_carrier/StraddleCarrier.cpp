#include "harbour/machines/straddle_carrier/StraddleCarrier.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/machines/GantryCrane.h"
#include "harbour/machines/parts/DriveReadings.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

constexpr double kG = core::kStandardGravity;
// the indicators a straddle carrier publishes, in snapshot order
constexpr const char* kIndicators[] = {"speed_kmh",   "spreader_size_ft",   "lamp_landed",
                                       "lamp_locked", "lamp_unlocked",      "horn",
                                       "load_t",      "net_load_t",         "lamp_brake_fault",
                                       "reversing",   "lamp_parking_brake", "spreader_length_m",
                                       "steering"};

// the spreader's frame in the portal's: its length (its y) along the portal's x
core::Mat3 spreader_on_portal() {
  return core::Mat3::rotation({0, 0, 1}, -0.5 * std::numbers::pi);
}

}  // namespace

StraddleCarrierSlots::StraddleCarrierSlots(const scene::ControlTable& t)
    : hoist(t.slot("hoist", scene::ControlKind::kAxis)),
      lock(t.slot("lock", scene::ControlKind::kButton)),
      unlock(t.slot("unlock", scene::ControlKind::kButton)),
      spreader_20(t.slot("spreader_20", scene::ControlKind::kButton)),
      spreader_40(t.slot("spreader_40", scene::ControlKind::kButton)),
      spreader_45(t.slot("spreader_45", scene::ControlKind::kButton)) {}

StraddleCarrier::StraddleCarrier(physics::PhysicsWorld& world, const StraddleCarrierSettings& s,
                                 const StraddleCarrierStart& start)
    : world_(world),
      settings_(s),
      slots_(s.controls),
      yard_(start.position_m.z),
      cab_(s.controls, s.steer_rate_per_s),
      body_([&] {
        // the portal settled on its tyres under its own and the spreader's weight (it starts at rest)
        const std::vector<SupportSpring> springs = tyre_springs(s.chassis);
        const Settling settled = settle(springs, (s.mass_kg + s.rig.spreader.mass_kg) * kG, {});
        physics::BoxSettings portal;
        portal.mass_kg = s.mass_kg;
        portal.half_extents_m = s.half_extents_m;
        portal.pose = {core::Mat3::rotation({0, 0, 1}, start.heading_rad),
                       start.position_m + core::Vec3{0.0, 0.0, -s.ground_z_m() - settled.sag_m}};
        portal.collides = false;
        return world.add_box(portal);
      }()),
      chassis_(s.chassis, body_) {
  // it touches the world by its sills, its legs and its top frame; the row it straddles passes between
  const double ground = s.ground_z_m();
  const auto beam = [&](const core::Vec3& half, const core::Vec3& centre) {
    world.add_box_shape(body_, half, {core::Mat3::identity(), centre}, scene::kSurfaceVehicle);
  };
  const double half_width = 0.5 * s.leg_width_m;
  for (const double side : {-1.0, 1.0}) {
    const double y = side * s.leg_y_m;
    beam({s.leg_x_m + half_width, half_width, 0.5 * (s.sill_top_m - s.sill_bottom_m)},
         {0.0, y, ground + 0.5 * (s.sill_bottom_m + s.sill_top_m)});
    for (const double end : {-1.0, 1.0})
      beam({half_width, half_width, 0.5 * (s.top_frame_m - s.sill_top_m)},
           {end * s.leg_x_m, y, ground + 0.5 * (s.sill_top_m + s.top_frame_m)});
    beam({s.leg_x_m + half_width, half_width, 0.5}, {0.0, y, ground + s.top_frame_m + 0.5});
  }
  const core::Pose portal = world.pose(body_);
  const core::Vec3 spreader_at{portal.position.x, portal.position.y, start.position_m.z + start.spreader_z_m};
  rig_ = std::make_unique<SpreaderHoist>(world, s.rig, std::vector<physics::BodyId>{body_},
                                         core::Pose{portal.rotation * spreader_on_portal(), spreader_at});
  wind_areas_[0] = {rig_->spreader_body(), rig_->spreader().half_extents_m(), true};
  // the portal as a box of its height whose faces have its areas
  const double half_height = 0.5 * (s.top_frame_m + 1.0);
  wind_areas_[1] = {
      body_,
      {0.25 * s.wind_area_side_m2 / half_height, 0.25 * s.wind_area_front_m2 / half_height, half_height}};
}

double StraddleCarrier::forward_mps() const {
  return chassis_.road_speed_mps(world_);
}

core::Vec3 StraddleCarrier::plumb_m() const {
  const core::Vec3 p = world_.pose(body_).position;
  return {p.x, p.y, 0.0};
}

core::Pose StraddleCarrier::cab_pose() const {
  const core::Pose portal = world_.pose(body_);
  return {portal.rotation, portal.to_parent(settings_.cab_position_m)};
}

void StraddleCarrier::step(const scene::Controls& raw, std::span<const ContainerRef> containers,
                           double dt_s) {
  const scene::Controls c = settings_.controls.in_range(raw);
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  chassis_.step(world_, cab_.step(c, dt_s), *ground_);
  SpreaderHoistCommand hoist;
  hoist.hoist = at(slots_.hoist);
  hoist.lock = at(slots_.lock) != 0.0;
  hoist.unlock = at(slots_.unlock) != 0.0;
  hoist.emergency_stop = cab_.emergency_stop();
  hoist.spreader_size_ft = at(slots_.spreader_20) != 0.0   ? 20
                           : at(slots_.spreader_40) != 0.0 ? 40
                           : at(slots_.spreader_45) != 0.0 ? 45
                                                           : 0;
  rig_->step(hoist, containers, dt_s);
  wind_areas_[0].half_extents_m = rig_->spreader().half_extents_m();
}

void StraddleCarrier::settle_at_rest() {
  const physics::BodyId bodies[] = {body_, rig_->spreader_body()};
  settle_gantry_crane(*this, world_, bodies, *rig_);
}

void StraddleCarrier::describe(scene::SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"portal", "straddle_carrier.portal", settings_.half_extents_m});
  d.entities.push_back({"spreader", "straddle_carrier.spreader", rig_->spreader().half_extents_m()});
  d.indicators.assign(std::begin(kIndicators), std::end(kIndicators));
  d.drives = {"hoist", "engine"};
  d.rope_count = std::min(rig_->hoist().rope_count(), scene::kMaxRopes);
}

int StraddleCarrier::publish(scene::Snapshot& s, int first) const {
  int n = first;
  for (const core::Pose& pose : {world_.pose(body_), spreader_pose()})
    if (n < scene::kMaxEntities) {
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), 0, pose};
      ++n;
    }
  publish_ropes(rig_->hoist(), s);
  const TwistlockLamps lamps = rig_->locks().twistlocks().lamps();
  const double values[] = {forward_mps() * 3.6,
                           size_ft(rig_->spreader_state().size),
                           lamps.landed ? 1.0 : 0.0,
                           lamps.locked ? 1.0 : 0.0,
                           lamps.unlocked ? 1.0 : 0.0,
                           cab_.horn() ? 1.0 : 0.0,
                           rig_->hoisted_load_n() / kG / 1000.0,
                           rig_->net_load_t(),
                           rig_->brake_fault() ? 1.0 : 0.0,
                           cab_.direction() < 0 ? 1.0 : 0.0,
                           cab_.parking_brake() ? 1.0 : 0.0,
                           rig_->spreader_state().length_m,
                           cab_.steering()};
  static_assert(std::size(values) == std::size(kIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  const scene::Snapshot::Drive drives[] = {drum_reading(rig_->hoist(), 0), chassis_.engine()};
  publish_drives(drives, s);
  return n - first;
}

MachineTally StraddleCarrier::tally() const {
  MachineTally t;
  const core::Vec3 spreader = spreader_pose().position, plumb = plumb_m();
  t.swing_m = {spreader.x - plumb.x, spreader.y - plumb.y, 0.0};
  t.axes[0] = {"drive", forward_mps()};
  t.axes[1] = {"hoist", rig_->hoist().drum_rope_speed(0)};
  t.limit_hits = rig_->limit_hits();
  t.hoist_power_w = std::max(0.0, rig_->hoist().drum_power_w(0));
  t.travel_power_w = std::max(0.0, chassis_.drive_power_w());
  t.vehicle = true;
  return t;
}

Telemetry StraddleCarrier::telemetry() const {
  const MachineTally t = tally();
  return {core::length(t.swing_m),
          rig_->hoist().highest_tension_n(),
          {t.axes[0], AxisSpeed{"hoist", rig_->hoisting_speed_mps()}}};
}

void StraddleCarrier::drain_events(StepEvents& events) {
  rig_->locks().twistlocks().drain_events(events.twistlocks);
  rig_->hoist().drain_events(events.ropes);
}

void StraddleCarrier::inject_fault(MachineFault fault, int detail) {
  if (fault == MachineFault::kHoistBrake) rig_->inject_brake_fault();
  if (fault == MachineFault::kLandedSensor) rig_->inject_landed_sensor_fault(detail);
}

bool StraddleCarrier::fault_active(MachineFault fault) const {
  return fault == MachineFault::kHoistBrake     ? rig_->brake_fault()
         : fault == MachineFault::kLandedSensor ? rig_->landed_sensor_fault()
                                                : false;
}

void StraddleCarrier::hash_into(core::StateHash& hash) const {
  rig_->hoist().hash_into(hash);
  hash.add(cab_.steering());
  hash.add(cab_.horn());
  hash.add(rig_->locks().twistlocks().lamps());
  hash.add(rig_->spreader_state().length_m);
}

template <typename Self, typename Archive>
void StraddleCarrier::archive(Self& self, Archive& ar) {
  ar.section(0x53434152, "straddle carrier");  // "SCAR"
  ar.part(self.cab_);
  ar.part(*self.rig_);
}

void StraddleCarrier::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void StraddleCarrier::restore_state(core::StateReader& in) {
  archive(*this, in);
  wind_areas_[0].half_extents_m = rig_->spreader().half_extents_m();
}

}  // namespace harbour::sim
