#include "harbour/machines/tractor/TerminalTractor.h"

#include "harbour/machines/parts/DriveReadings.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

constexpr const char* kTractorIndicators[] = {"speed_kmh",         "gear",    "steering",        "horn",
                                              "direction",         "coupled", "hitch_angle_deg", "reversing",
                                              "lamp_parking_brake"};

physics::BodyId add_body(physics::PhysicsWorld& world, double mass_kg, const core::Vec3& half_extents_m,
                         const core::Pose& pose, const core::Vec3& center_of_mass_m = {}) {
  physics::BoxSettings box;
  box.mass_kg = mass_kg;
  box.half_extents_m = half_extents_m;
  box.pose = pose;
  box.center_of_mass_m = center_of_mass_m;
  box.surface = scene::kSurfaceVehicle;
  return world.add_box(box);
}

}  // namespace

// Where the tractor and its trailer stand at the start: settled on their tyres, the trailer's front on the
// plate (the small-angle statics of both bodies on their springs, solved in turn until they agree).
TerminalTractor::StartPoses TerminalTractor::start_poses(const TractorSettings& s,
                                                         const TractorStart& start) {
  constexpr double kG = core::kStandardGravity;
  const auto level_springs = [](const WheeledChassisSettings& c) {
    // each tyre's gap to the ground with the body level and the first axle's tyres just touching
    std::vector<SupportSpring> springs = tyre_springs(c);
    for (std::size_t n = 0; n < springs.size(); ++n)
      springs[n].base_drop_m = c.axles[n].hub_z_m - c.axles.front().hub_z_m;
    return springs;
  };
  const double tractor_z = s.chassis.tyre.radius_m - s.chassis.axles.front().hub_z_m;
  const core::Mat3 heading = core::Mat3::rotation({0, 0, 1}, start.heading_rad);
  const auto pose = [&](double z, const Settling& settled, const core::Vec3& xy) {
    return core::Pose{heading * core::Mat3::rotation({0, 1, 0}, settled.pitch_rad),
                      {xy.x, xy.y, z - settled.sag_m}};
  };
  Settling tractor = settle(level_springs(s.chassis), s.mass_kg * kG, {});
  StartPoses poses{pose(tractor_z, tractor, start.position_m), {}};
  if (!start.trailer) return poses;
  const TrailerSettings& t = *start.trailer;
  const double trailer_z = t.wheels.tyre.radius_m - t.wheels.axles.front().hub_z_m;
  const double plate_k = s.fifth_wheel.stiffness_n_per_m;
  Settling trailer;
  for (int pass = 0; pass < 5; ++pass) {
    const double hitch_z = tractor_z + s.hitch_m.z - tractor.sag_at(s.hitch_m.x);
    std::vector<SupportSpring> springs = level_springs(t.wheels);
    springs.push_back({t.kingpin_m.x, plate_k, trailer_z + t.kingpin_m.z - hitch_z});
    trailer = settle(springs, 0.0, {{t.center_of_mass_x_m, t.mass_kg * kG}});
    const double kingpin_n = plate_k * (trailer.sag_at(t.kingpin_m.x) - springs.back().base_drop_m);
    tractor = settle(level_springs(s.chassis), s.mass_kg * kG, {{s.hitch_m.x, kingpin_n}});
  }
  poses.tractor = pose(tractor_z, tractor, start.position_m);
  const core::Vec3 hitch = poses.tractor.to_parent(s.hitch_m);
  poses.trailer = pose(trailer_z, trailer, hitch - heading * t.kingpin_m);
  return poses;
}

TerminalTractor::TerminalTractor(physics::PhysicsWorld& world, const TractorSettings& settings,
                                 const TractorStart& start)
    : TerminalTractor(world, settings, start, start_poses(settings, start)) {}

TerminalTractor::TerminalTractor(physics::PhysicsWorld& world, const TractorSettings& settings,
                                 const TractorStart& start, const StartPoses& poses)
    : world_(world),
      settings_(settings),
      cab_(settings.controls, settings.steer_rate_per_s),
      couple_slot_(settings.controls.slot("couple", scene::ControlKind::kButton)),
      body_(add_body(world, settings.mass_kg, settings.half_extents_m, poses.tractor)),
      chassis_(settings.chassis, body_),
      wind_areas_{WindArea{body_, settings.half_extents_m}, WindArea{}} {
  if (!start.trailer) return;
  // in line behind it, its kingpin on the lifted plate, locked in the jaw
  const TrailerSettings& t = *start.trailer;
  trailer_body_ =
      add_body(world, t.mass_kg, t.half_extents_m, poses.trailer, {t.center_of_mass_x_m, 0.0, 0.0});
  world.exclude_contacts(body_, trailer_body_);  // its front reaches over the chassis
  trailer_wheels_.emplace(t.wheels, trailer_body_);
  if (t.legs) trailer_legs_.emplace(*t.legs, trailer_body_);
  trailer_id_ = t.id;
  trailer_kingpin_m_ = t.kingpin_m;
  trailer_half_extents_m_ = t.half_extents_m;
  trailer_look_ = t.look;
  payload_half_extents_m_ = t.payload_half_extents_m;
  payload_id_ = t.payload_id;
  wind_areas_[1] = {trailer_body_, t.half_extents_m};
  if (t.receives_half_extents_m) {
    // parked still under the quay until a crane hands it over
    physics::BoxSettings box;
    box.mass_kg = 1000.0;  // its gross mass comes with it
    box.half_extents_m = *t.receives_half_extents_m;
    box.pose = {poses.trailer.rotation, poses.trailer.position - core::Vec3{0, 0, 100.0}};
    box.kinematic = true;
    box.surface = scene::kSurfaceContainer;
    load_body_ = world.add_box(box);
    load_half_extents_m_ = *t.receives_half_extents_m;
    world.exclude_contacts(load_body_, trailer_body_);  // the cones hold it
  }
  coupled_ = true;
  lift_ = lift_target_ = 1.0;
}

core::Vec3 TerminalTractor::kingpin_m() const {
  if (trailer_body_ == physics::kWorld) return {};
  return world_.pose(trailer_body_).to_parent(trailer_kingpin_m_);
}

core::Vec3 TerminalTractor::jaw_m() const {
  const FifthWheelSettings& w = settings_.fifth_wheel;
  return world_.pose(body_).to_parent(settings_.hitch_m - core::Vec3{0, 0, (1.0 - lift_) * w.lift_m});
}

std::optional<physics::BodyId> TerminalTractor::held_item() const {
  if (coupled_) return trailer_body_;
  return std::nullopt;
}

std::vector<std::pair<std::string, physics::BodyId>> TerminalTractor::own_items() const {
  if (trailer_body_ == physics::kWorld) return {};
  return {{trailer_id_, trailer_body_}};
}

void TerminalTractor::step_coupling(bool couple_pressed, double dt_s) {
  const FifthWheelSettings& w = settings_.fifth_wheel;
  if (couple_pressed && !couple_was_pressed_) {
    if (coupled_) {
      // drop: at a standstill, onto legs it has
      if (std::abs(forward_mps()) < w.standstill_mps && trailer_legs_) lift_target_ = 0.0;
    } else {
      // couple: the kingpin within the jaw's reach across and not below the plate
      const core::Vec3 jaw = jaw_m(), kingpin = kingpin_m();
      const core::Vec3 across{kingpin.x - jaw.x, kingpin.y - jaw.y, 0.0};
      if (std::sqrt(dot(across, across)) <= w.capture_m && kingpin.z >= jaw.z - 0.05) {
        coupled_ = true;
        capture_offset_m_ = across;
        lift_target_ = 1.0;
      }
    }
  }
  couple_was_pressed_ = couple_pressed;
  const double most = w.lift_rate_mps / w.lift_m * dt_s;
  lift_ += std::clamp(lift_target_ - lift_, -most, most);
  if (coupled_ && lift_target_ == 0.0 && lift_ == 0.0) coupled_ = false;  // down: the jaw opens
  // the jaw draws a captured kingpin home
  const double offset = std::sqrt(dot(capture_offset_m_, capture_offset_m_));
  if (offset > 0.0)
    capture_offset_m_ = capture_offset_m_ * (std::max(0.0, offset - w.capture_rate_mps * dt_s) / offset);
}

void TerminalTractor::push_coupling() {
  // the plate carries the kingpin from below; the locked jaw holds it across
  if (!coupled_) return;
  const FifthWheelSettings& w = settings_.fifth_wheel;
  const core::Vec3 jaw = jaw_m(), kingpin = kingpin_m();
  const core::Vec3 v = world_.point_velocity(body_, world_.pose(body_).to_local(jaw)) -
                       world_.point_velocity(trailer_body_, trailer_kingpin_m_);
  core::Vec3 f{w.stiffness_n_per_m * (jaw.x + capture_offset_m_.x - kingpin.x) + w.damping_ns_per_m * v.x,
               w.stiffness_n_per_m * (jaw.y + capture_offset_m_.y - kingpin.y) + w.damping_ns_per_m * v.y,
               0.0};
  const double sag = jaw.z - kingpin.z;
  if (sag > 0.0) f.z = std::max(0.0, w.stiffness_n_per_m * sag + w.damping_ns_per_m * v.z);
  world_.add_force_at(trailer_body_, kingpin, f);
  world_.add_force_at(body_, jaw, f * -1.0);
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

void TerminalTractor::step(const scene::Controls& raw, std::span<const ContainerRef>, double dt_s) {
  const scene::Controls c = settings_.controls.in_range(raw);
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  const ChassisCommand command = cab_.step(c, dt_s);
  chassis_.step(world_, command, *ground_);
  if (!trailer_wheels_) return;
  step_coupling(at(couple_slot_) != 0.0, dt_s);
  push_coupling();
  // the trailer's brakes work with the tractor's while coupled (air brakes; the parking brake's valve applies
  // them fully, as a tractor's hand control valve does); dropped, its spring brakes hold
  const double trailer_brake = !coupled_ || command.parking_brake ? 1.0 : command.brake;
  trailer_wheels_->step(world_, {0.0, false, trailer_brake, 0.0}, *ground_);
  if (trailer_legs_) trailer_legs_->step(world_, {0.0, false, 1.0, 0.0}, *ground_);
  const bool folded = coupled_ && std::abs(hitch_angle_rad()) > settings_.jackknife_angle_rad;
  if (folded && !jackknifed_) ++jackknifes_;
  jackknifed_ = folded;
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
  t.travel_power_w = std::max(0.0, chassis_.drive_power_w());
  t.vehicle = true;
  t.jackknifes = jackknifes_;
  return t;
}

std::string TerminalTractor::why_no_load() const {
  if (load_body_ == physics::kWorld) return "its trailer takes no load handed over (trailer.receives)";
  if (loaded_) return "its trailer already carries the load handed over";
  return "";
}

void TerminalTractor::take_load(const core::Pose& on_trailer, double mass_kg) {
  const core::Pose trailer = world_.pose(trailer_body_);
  const core::Pose at{trailer.rotation * on_trailer.rotation, trailer.to_parent(on_trailer.position)};
  world_.set_kinematic_motion(load_body_, at, world_.point_velocity(trailer_body_, on_trailer.position),
                              world_.angular_velocity(trailer_body_));
  world_.set_box_mass(load_body_, mass_kg, load_half_extents_m_);
  world_.set_kinematic(load_body_, false);
  world_.attach(load_body_, trailer_body_);
  loaded_ = true;
  load_mass_kg_ = mass_kg;
}

std::optional<physics::BodyId> TerminalTractor::load() const {
  if (loaded_) return load_body_;
  return std::nullopt;
}

void TerminalTractor::describe(scene::SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"tractor", "tractor.chassis", settings_.half_extents_m});
  if (trailer_body_ != physics::kWorld)
    d.entities.push_back({"trailer", trailer_look_, trailer_half_extents_m_});
  if (load_body_ != physics::kWorld)
    d.entities.push_back(
        {scene::kTrailerLoad, scene::container_look(2.0 * load_half_extents_m_.x), load_half_extents_m_});
  if (payload_half_extents_m_)
    d.entities.push_back(
        {payload_id_, scene::container_look(2.0 * payload_half_extents_m_->x), *payload_half_extents_m_});
  d.indicators.assign(std::begin(kTractorIndicators), std::end(kTractorIndicators));
  d.drives = {"engine"};
  d.rope_count = 0;
}

int TerminalTractor::publish(scene::Snapshot& s, int first) const {
  int n = first;
  for (const physics::BodyId b : {body_, trailer_body_, load_body_})
    if (b != physics::kWorld && n < scene::kMaxEntities) {
      const std::uint32_t flags = b == load_body_ && !loaded_ ? scene::Snapshot::kHidden : 0;
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), flags, world_.pose(b)};
      ++n;
    }
  if (payload_half_extents_m_ && n < scene::kMaxEntities) {  // standing on the deck's top, riding it
    const core::Pose deck = world_.pose(trailer_body_);
    const core::Vec3 on_deck{0.0, 0.0, trailer_half_extents_m_.z + payload_half_extents_m_->z};
    s.entities[static_cast<std::size_t>(n)] = {
        static_cast<std::uint32_t>(n), 0, {deck.rotation, deck.to_parent(on_deck)}};
    ++n;
  }
  const double speed = forward_mps();
  const double values[] = {
      speed * 3.6,
      static_cast<double>(drivetrain_wheel_torque_nm(settings_.chassis.drivetrain,
                                                     settings_.chassis.tyre.radius_m, 1.0, speed)
                              .second),
      cab_.steering(),
      cab_.horn() ? 1.0 : 0.0,
      static_cast<double>(cab_.direction()),
      coupled_ ? 1.0 : 0.0,
      coupled_ ? hitch_angle_rad() * 180.0 / std::numbers::pi : 0.0,
      cab_.direction() < 0 ? 1.0 : 0.0,
      cab_.parking_brake() ? 1.0 : 0.0};
  static_assert(std::size(values) == std::size(kTractorIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  const scene::Snapshot::Drive engine[] = {chassis_.engine()};
  publish_drives(engine, s);
  return n - first;
}

void TerminalTractor::hash_into(core::StateHash& hash) const {
  hash.add(cab_.steering());
  hash.add(cab_.horn());
  hash.add(jackknifes_);
  hash.add(coupled_);
  hash.add(lift_);
  hash.add(lift_target_);
  hash.add(capture_offset_m_.x);
  hash.add(capture_offset_m_.y);
  if (load_body_ == physics::kWorld) return;  // (tractors without one hash as they did)
  hash.add(loaded_);
  hash.add(load_mass_kg_);
}

template <typename Self, typename Archive>
void TerminalTractor::archive(Self& self, Archive& ar) {
  ar.section(0x54524332, "terminal tractor");  // "TRC2"
  ar.part(self.cab_);
  ar(self.jackknifed_, self.jackknifes_, self.coupled_, self.couple_was_pressed_, self.lift_,
     self.lift_target_, self.capture_offset_m_);
  if (self.load_body_ == physics::kWorld) return;
  ar.section(0x5452434C, "tractor's load");  // "TRCL": the load handed over
  ar(self.loaded_, self.load_mass_kg_);
}

void TerminalTractor::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void TerminalTractor::restore_state(core::StateReader& in) {
  archive(*this, in);
  if (load_body_ != physics::kWorld && loaded_)
    world_.set_box_mass(load_body_, load_mass_kg_, load_half_extents_m_);
}

}  // namespace harbour::sim
