#include "harbour/sim/Simulation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "harbour/core/StateHash.h"
#include "harbour/core/Units.h"
#include "harbour/scene/HandSignals.h"

namespace harbour::sim {
namespace {
constexpr const char* kEmergencyStopControl = "emergency_stop";  // every machine's (its control table)
constexpr std::uint32_t kSimulationSectionV2 = 0x53494D32;       // "SIM2": with solver-message warnings
constexpr std::uint32_t kSimulationSectionV3 = 0x53494D33;       // "SIM3": and the instructor's stop
constexpr std::uint32_t kSimulationSectionV4 = 0x53494D34;       // "SIM4": and the events from the first lift
constexpr std::uint32_t kSimulationSection = 0x53494D35;         // "SIM5": and the supply (power failure)
constexpr std::uint32_t kSimulationSectionV6 = 0x53494D36;       // "SIM6": SIM5 and the team obstacles' sizes
}  // namespace

namespace {

constexpr double kMarkingHalfThickness_m = 0.005;  // a painted bay, drawn as a thin plate on the ground

// the machine as the run was built: old runs on the models they were recorded with
MachineSetup as_built(const ScenarioSettings& scenario) {
  MachineSetup setup = scenario.machine;
  for (cable::ReevingSettings* reeving : setup.reevings()) {
    reeving->stretch_along_chord |= scenario.ropes_stretch_along_chord;
    reeving->damping_against_ground |= scenario.rope_damping_against_ground;
    reeving->sheaves_without_bending_loss |= scenario.sheaves_without_bending_loss;
    reeving->simple_sheaves |= scenario.simple_sheaves;
    reeving->slack_ropes_straighten |= scenario.slack_ropes_straighten;
  }
  if (scenario.end_stops_at_travel) setup.end_stops_at_travel();
  return setup;
}
}  // namespace

Simulation::Simulation(const ScenarioSettings& scenario)
    : scenario_(scenario), weather_(scenario.weather, scenario.seed) {
  world_ = std::make_unique<physics::PhysicsWorld>(physics::WorldSettings{});
  if (scenario.vessel) {
    // the quay apron up to its edge, the harbour bed under the water
    constexpr double kQuayDepth_m = 20.0, kQuayLand_m = 500.0;
    world_->add_static_box(
        {kQuayLand_m / 2, kQuayLand_m, kQuayDepth_m / 2},
        {core::Mat3::identity(), {scenario.quay_edge_x_m - kQuayLand_m / 2, 0.0, -kQuayDepth_m / 2}},
        scene::kSurfaceQuay);
    world_->add_ground(-kQuayDepth_m, scene::kSurfaceGround);
    vessel_ = std::make_unique<Vessel>(*world_, *scenario.vessel);
  } else {
    world_->add_ground(0.0, scene::kSurfaceQuay);
  }
  for (const StaticBlock& b : scenario.blocks) {
    core::Pose p;
    p.position = b.position_m;
    world_->add_static_box(b.half_extents_m, p, scene::kSurfaceQuay);
  }
  for (const ContainerPlacement& c : scenario.containers) {
    physics::BoxSettings box;
    box.half_extents_m = c.half_extents_m;
    box.mass_kg = c.gross_mass_kg;
    box.pose = c.pose;
    box.center_of_mass_m = c.center_of_mass_m;
    box.surface = c.kind == ContainerPlacement::Kind::kHatchCover ? scene::kSurfaceHatchCover
                                                                  : scene::kSurfaceContainer;
    box.kinematic = true;
    containers_.push_back({world_->add_box(box), c.half_extents_m, c.pocket_half_length_m,
                           c.pocket_half_width_m, c.end_pocket_half_length_m});
    secured_.push_back(true);
    stowed_.push_back(c.on_vessel && vessel_
                          ? core::Pose{vessel_->frame().rotation.transposed() * c.pose.rotation,
                                       vessel_->frame().to_local(c.pose.position)}
                          : c.pose);
  }
  if (scenario.trucks.trucks > 0) trucks_ = std::make_unique<TruckLane>(*world_, scenario.trucks);
  obstacles_ = std::make_unique<TeamObstacles>(*world_);
  machine_ = as_built(scenario).build(*world_);
  if (!scenario.ropes_start_unstretched) machine_->settle_ropes();
  if (!scenario.ropes_start_unstretched && !scenario.start_unsettled) machine_->settle_at_rest();
  if (scenario.ramp) {
    ramp_ = std::make_unique<RoRoRamp>(*scenario.ramp);
    ramp_->move_to(0.0);
    machine_->stand_on(*ramp_);
  }
  if (scenario.bulk) {
    bulk_ = bulk::build_bulk_world(*scenario.bulk, vessel_motion());
    if (const BulkTool* tool = machine_->bulk_tool()) bulk_grab_ = bulk_->add_grab(tool->grab);
  }
  // event buffers sized once: a step appends to them without allocating
  events_.impacts.reserve(256);
  events_.twistlocks.reserve(64);
  events_.ropes.reserve(256);
  cab_velocity_ = world_->point_velocity(machine_->cab_body(), machine_->eye_on_cab_body_m());
  scene::SceneDescription described;
  machine_->describe(described);
  roped_ = described.rope_count > 0;
}

void Simulation::apply_due_events() {
  while (next_event_ < scenario_.events.size() && scenario_.events[next_event_].at_s <= clock_.time_s()) {
    const ScriptedEvent& e = scenario_.events[next_event_++];
    apply_event(e, e.at_s);
  }
  if (scenario_.lift_events.empty()) return;
  if (first_lift_step_ < 0 && carrying()) first_lift_step_ = clock_.steps();
  if (first_lift_step_ < 0) return;
  const double lifted_s = static_cast<double>(clock_.steps() - first_lift_step_) * kStep_s;
  while (next_lift_event_ < scenario_.lift_events.size() &&
         scenario_.lift_events[next_lift_event_].at_s <= lifted_s) {
    const ScriptedEvent& e = scenario_.lift_events[next_lift_event_++];
    apply_event(e, static_cast<double>(first_lift_step_) * kStep_s + e.at_s);
  }
}

bool Simulation::carrying() const {
  return machine_->held_item().has_value() ||
         (bulk_ && bulk_grab_ >= 0 && bulk_->grab(bulk_grab_).load_m3 > 0.0);
}

void Simulation::apply_event(const ScriptedEvent& e, double at_s) {
  switch (e.kind) {
    case ScriptedEvent::Kind::kGust: {
      Gust g = e.gust;
      g.start_s = at_s;
      weather_.add_gust(g);
      break;
    }
    case ScriptedEvent::Kind::kHoistBrakeFault:
      if (machine_->has_fault(MachineFault::kHoistBrake))
        machine_->inject_fault(MachineFault::kHoistBrake, 0);
      break;
    case ScriptedEvent::Kind::kLandedSensorFault:
      if (machine_->has_fault(MachineFault::kLandedSensor))
        machine_->inject_fault(MachineFault::kLandedSensor, e.corner);
      break;
    case ScriptedEvent::Kind::kLimiterFault:
      if (machine_->has_fault(MachineFault::kLoadMomentLimiter))
        machine_->inject_fault(MachineFault::kLoadMomentLimiter, 0);
      break;
  }
}

std::string why_invalid(const InstructorCommand& c) {
  using Kind = InstructorCommand::Kind;
  switch (c.kind) {
    case Kind::kGust:
      if (!(c.gust.duration_s > 0.0 && c.gust.duration_s <= kMaxGustDuration_s &&
            c.gust.amplitude_mps > 0.0 && c.gust.amplitude_mps <= kMaxGust_mps))
        return "a gust lasts up to " + std::to_string(static_cast<int>(kMaxGustDuration_s)) +
               " s and peaks at 0-" + std::to_string(static_cast<int>(kMaxGust_mps)) + " m/s over the mean";
      break;
    case Kind::kLandedSensorFault:
      if (c.corner < 0 || c.corner >= kTwistlockCorners) return "a twistlock corner is 0-3";
      break;
    case Kind::kSetWind:
      if (!(c.wind_mean_mps >= 0.0 && c.wind_mean_mps <= kMaxMeanWind_mps && c.turbulence >= 0.0 &&
            c.turbulence <= 1.0 && c.wind_from_rad >= 0.0 && c.wind_from_rad <= 2.0 * std::numbers::pi))
        return "wind 0-" + std::to_string(static_cast<int>(kMaxMeanWind_mps)) +
               " m/s from 0-360 deg, turbulence intensity 0-1";
      break;
    case Kind::kSetVisibility:
      if (!(c.value > 0.0 && c.value <= kMaxVisibility_m)) return "visibility 0-100 km";
      break;
    case Kind::kSetRain:
      if (!(c.value >= 0.0 && c.value <= kMaxRain_mm_per_h)) return "rain 0-500 mm/h";
      break;
    case Kind::kSetCloud:
      if (!(c.value >= 0.0 && c.value <= kOvercast_oktas)) return "cloud cover 0-8 oktas";
      break;
    case Kind::kSetTimeOfDay:
      if (!(c.value >= 0.0 && c.value < kHoursPerDay)) return "time of day 0-24 h";
      break;
    case Kind::kSignal:
      if (!(c.value >= 0.0 && c.value < static_cast<double>(scene::hand_signals().size()) &&
            c.value == std::floor(c.value)))
        return "a hand signal is one of " + scene::hand_signal_names();
      break;
    case Kind::kHoistBrakeFault:
    case Kind::kLimiterFault:
    case Kind::kClearFaults:
    case Kind::kEmergencyStop:
    case Kind::kReleaseEmergencyStop:
    case Kind::kPowerFailure:
    case Kind::kPowerRestored:
      break;
    default:
      return "unknown command kind " + std::to_string(static_cast<int>(c.kind));
  }
  return {};
}

namespace {
std::optional<MachineFault> fault_of(const InstructorCommand& c) {
  using Kind = InstructorCommand::Kind;
  return c.kind == Kind::kHoistBrakeFault     ? std::optional(MachineFault::kHoistBrake)
         : c.kind == Kind::kLandedSensorFault ? std::optional(MachineFault::kLandedSensor)
         : c.kind == Kind::kLimiterFault      ? std::optional(MachineFault::kLoadMomentLimiter)
                                              : std::nullopt;
}
const scene::HandSignal& signal_of(const InstructorCommand& c) {
  return scene::hand_signals()[static_cast<std::size_t>(c.value)];  // why_invalid checked it
}
}  // namespace

std::string Simulation::why_refused(const InstructorCommand& c) const {
  if (std::string why = why_invalid(c); !why.empty()) return why;
  if (const auto fault = fault_of(c); fault && !machine_->has_fault(*fault))
    return std::string("the ") + machine_->kind() + " has no such part to fail";
  using Kind = InstructorCommand::Kind;
  const bool stops = c.kind == Kind::kEmergencyStop || c.kind == Kind::kReleaseEmergencyStop ||
                     c.kind == Kind::kPowerFailure || c.kind == Kind::kPowerRestored;
  if (stops && control_table().find(kEmergencyStopControl) < 0)
    return std::string("the ") + machine_->kind() + " has no emergency stop (nothing to cut its drives)";
  if (c.kind == Kind::kSignal)
    if (const std::string why = scene::why_not_for(signal_of(c), control_table()); !why.empty())
      return std::string("the ") + machine_->kind() + " has " + why;
  return "";
}

std::string TeamInput::item_name() const {
  const auto end = std::find(item.begin(), item.end(), '\0');
  return {item.begin(), end};
}

bool TeamInput::name_item(std::string_view name) {
  item.fill('\0');
  if (name.size() > kMostItemChars) return false;
  std::copy(name.begin(), name.end(), item.begin());
  return true;
}

std::string why_invalid(const TeamInput& t) {
  const core::Vec3 p = t.pose.position, v = t.velocity_mps, w = t.angular_velocity_radps;
  for (const double x : {p.x, p.y, p.z, v.x, v.y, v.z, w.x, w.y, w.z, t.mass_kg})
    if (!std::isfinite(x)) return "a number that is not finite";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(t.pose.rotation.m[r][c])) return "a number that is not finite";
  if (static_cast<std::uint8_t>(t.kind) >= TeamInput::kKinds) return "an unknown kind";
  if (t.slot < 0) return "a negative slot";
  if (std::abs(p.x) > 1e5 || std::abs(p.y) > 1e5 || std::abs(p.z) > 1e5) return "a place beyond 100 km";
  if (core::length(v) > 100.0 || core::length(w) > 10.0) return "a speed beyond 100 m/s or 10 rad/s";
  if (t.kind == TeamInput::Kind::kLoadOn && (t.mass_kg < 100.0 || t.mass_kg > 80000.0))
    return "a load's mass outside 100 kg - 80 t";
  const std::string item = t.item_name();
  if (!std::all_of(item.begin(), item.end(), [](char c) { return c > ' ' && c < 127; }) ||
      std::any_of(t.item.begin() + static_cast<std::ptrdiff_t>(item.size()), t.item.end(),
                  [](char c) { return c != 0; }))
    return "an item's name of other than printable ASCII";
  if (t.kind == TeamInput::Kind::kObstacleAt) {
    const core::Vec3 h = t.half_extents_m;
    if (t.slot >= TeamObstacles::kMostObstacles)
      return "an obstacle past " + std::to_string(TeamObstacles::kMostObstacles);
    for (const double x : {h.x, h.y, h.z})
      if (!std::isfinite(x) || x < 0.0 || x > 25.0) return "an obstacle's side outside 0-50 m";
  }
  return "";
}

std::string Simulation::why_refused(const TeamInput& t) const {
  if (std::string why = why_invalid(t); !why.empty()) return why;
  using Kind = TeamInput::Kind;
  if (t.kind == Kind::kLoadOn) return machine_->why_no_load();
  if (t.kind == Kind::kObstacleAt) return "";
  if (!trucks_ || !trucks_->team()) return "this exercise has no team trucks";
  if (t.slot >= trucks_->trucks()) return "no team truck " + std::to_string(t.slot + 1);
  if (t.kind == Kind::kTruckAt) return "";
  // kTakenOver: the box its cones hold
  if (trucks_->seated_box(t.slot) < 0) return "team truck " + std::to_string(t.slot + 1) + " holds no box";
  return trucks_->is_taken_over(t.slot) ? "its box was taken over already" : "";
}

void Simulation::team_input(const TeamInput& t) {
  if (const std::string why = why_refused(t); !why.empty()) throw std::invalid_argument("team input: " + why);
  switch (t.kind) {
    case TeamInput::Kind::kTruckAt:
      trucks_->set_truck(t.slot, t.pose, t.velocity_mps, t.angular_velocity_radps);
      break;
    case TeamInput::Kind::kTakenOver:
      trucks_->taken_over(t.slot);
      break;
    case TeamInput::Kind::kLoadOn:
      machine_->take_load(t.pose, t.mass_kg);
      break;
    case TeamInput::Kind::kObstacleAt:
      obstacles_->set(t.slot, t.half_extents_m, t.pose, t.velocity_mps, t.angular_velocity_radps);
      break;
  }
}

void Simulation::command(const InstructorCommand& c) {
  using Kind = InstructorCommand::Kind;
  if (const std::string why = why_refused(c); !why.empty())
    throw std::invalid_argument("instructor command: " + why);
  switch (c.kind) {
    case Kind::kGust: {
      Gust g = c.gust;
      g.start_s = clock_.time_s();
      weather_.add_gust(g);
      break;
    }
    case Kind::kHoistBrakeFault:
      machine_->inject_fault(MachineFault::kHoistBrake, 0);
      break;
    case Kind::kLandedSensorFault:
      machine_->inject_fault(MachineFault::kLandedSensor, c.corner);
      break;
    case Kind::kLimiterFault:
      machine_->inject_fault(MachineFault::kLoadMomentLimiter, 0);
      break;
    case Kind::kClearFaults:
      machine_->clear_faults();
      break;
    case Kind::kSetWind:
      weather_.set_wind(c.wind_mean_mps, c.wind_from_rad, c.turbulence);
      break;
    case Kind::kSetVisibility:
      weather_.set_visibility(c.value);
      break;
    case Kind::kSetRain:
      weather_.set_rain(c.value);
      break;
    case Kind::kSetCloud:
      weather_.set_cloud(c.value);
      break;
    case Kind::kSetTimeOfDay:
      weather_.set_time_of_day(c.value);
      break;
    case Kind::kEmergencyStop:
      instructor_stop_ = true;
      break;
    case Kind::kReleaseEmergencyStop:
      instructor_stop_ = false;
      break;
    case Kind::kPowerFailure:
      power_off_ = true;
      awaiting_zero_ = false;
      break;
    case Kind::kPowerRestored:
      if (power_off_) awaiting_zero_ = true;  // zero-voltage protection: no drive restarts under a held lever
      power_off_ = false;
      break;
    case Kind::kSignal:
      signal_ = {static_cast<int>(c.value), clock_.time_s(), signal_.count + 1};
      break;
  }
}

bool Simulation::levers_at_zero(const scene::Controls& controls) const {
  const scene::Controls read = control_table().in_range(controls);
  for (int slot = 0; slot < control_table().size(); ++slot) {
    const scene::ControlSpec& c = control_table()[slot];
    if (c.kind == scene::ControlKind::kAxis && std::abs(read.value[static_cast<std::size_t>(slot)] -
                                                        c.neutral) > kLeverZeroBand * (c.max - c.min) / 2)
      return false;
  }
  return true;
}

const ContainerRef* Simulation::liftable(physics::BodyId body) const {
  for (const ContainerRef& c : containers_)
    if (c.body == body) return &c;
  return nullptr;
}

void Simulation::apply_wind() {
  // drag on the machine's exposed parts and on the item it carries
  const core::Vec3 wind = weather_.wind();
  const double rho = scenario_.weather.air_density_kg_m3, cd = scenario_.drag_coefficient;
  const auto push = [&](physics::BodyId body, const core::Vec3& half_extents_m) {
    const core::Pose p = world_->pose(body);
    world_->add_force_at(body, p.position,
                         box_drag(wind, world_->linear_velocity(body), p, half_extents_m, cd, rho));
  };
  for (const WindArea& area : machine_->wind_areas())
    push(area.body, area.half_extents_m);
  if (const auto held = machine_->held_item())
    if (const ContainerRef* item = liftable(*held)) push(item->body, item->half_extents_m);
}

core::Vec3 Simulation::wind_rest_offset_m(const core::Vec3& wind, std::optional<physics::BodyId> box) const {
  const double rho = scenario_.weather.air_density_kg_m3, cd = scenario_.drag_coefficient;
  core::Vec3 force;
  double mass_kg = 0.0;
  const auto add = [&](physics::BodyId body, const core::Vec3& half_extents_m) {
    force += box_drag(wind, {}, world_->pose(body), half_extents_m, cd, rho);
    mass_kg += world_->mass_kg(body);
  };
  for (const WindArea& area : machine_->wind_areas())
    if (area.swings) add(area.body, area.half_extents_m);
  if (box)
    if (const ContainerRef* item = liftable(*box)) add(item->body, item->half_extents_m);
  if (mass_kg <= 0.0) return {};  // nothing hangs
  const double lean = machine_->pendulum_length_m() / (mass_kg * core::kStandardGravity);
  return {force.x * lean, force.y * lean, 0.0};
}

void Simulation::move_secured_cargo() {
  if (!vessel_) return;
  const core::Pose& vessel = vessel_->frame();
  const core::Vec3 &v = vessel_->velocity(), &w = vessel_->angular_velocity();
  const core::Vec3 centre = vessel_->waterline_centre();  // where v is the velocity
  for (std::size_t n = 0; n < containers_.size(); ++n) {
    if (!secured_[n] || !scenario_.containers[n].on_vessel) continue;
    // the body's reference is its centre of mass: place that, moving with the hull
    const core::Pose shape{vessel.rotation * stowed_[n].rotation, vessel.to_parent(stowed_[n].position)};
    const core::Pose body{shape.rotation, shape.to_parent(scenario_.containers[n].center_of_mass_m)};
    world_->set_kinematic_motion(containers_[n].body, body, v + cross(w, body.position - centre), w);
  }
}

void Simulation::release(std::size_t item) {
  // frees a secured item and, first, whatever is stacked on it (their locks and lashings go with it)
  if (!secured_[item]) return;
  secured_[item] = false;
  world_->set_kinematic(containers_[item].body, false);
  const core::Pose p = world_->pose(containers_[item].body);
  const core::Vec3& h = containers_[item].half_extents_m;
  for (std::size_t n = 0; n < containers_.size(); ++n) {
    if (!secured_[n]) continue;
    const core::Pose q = world_->pose(containers_[n].body);
    const core::Vec3 local = p.to_local(q.position);
    const double reach_x = h.x + containers_[n].half_extents_m.x,
                 reach_y = h.y + containers_[n].half_extents_m.y;
    const bool above = std::abs(local.z - h.z - containers_[n].half_extents_m.z) < 0.05;
    if (above && std::abs(local.x) < reach_x && std::abs(local.y) < reach_y) release(n);
  }
}

void Simulation::advance(const scene::Controls& controls) {
  if (world_->diverged()) return;  // stopped where it diverged
  // scripted events, weather and wind, the machine (drives, ropes, twistlocks) pushing on the bodies, then
  // the multibody step
  apply_due_events();
  weather_.step(kStep_s);
  apply_wind();
  if (vessel_) vessel_->move_to(clock_.time_s());
  if (ramp_) ramp_->move_to(clock_.time_s());
  move_secured_cargo();
  if (awaiting_zero_ && levers_at_zero(controls)) awaiting_zero_ = false;
  const int stop = control_table().find(kEmergencyStopControl);
  emergency_stop_ =
      instructor_stop_ ||
      (stop >= 0 && control_table().in_range(controls).value[static_cast<std::size_t>(stop)] != 0.0);
  if (instructor_stop_ || power_off_ || awaiting_zero_) {
    // the trainee's controls are recorded and evaluated as they were; the machine reads its stop pressed (a
    // dead supply acts as the stop does: drives off, brakes set)
    scene::Controls stopped = controls;
    stopped.value[static_cast<std::size_t>(control_table().find(kEmergencyStopControl))] = 1.0;
    machine_->step(stopped, containers_, kStep_s);
  } else {
    machine_->step(controls, containers_, kStep_s);
  }
  if (const auto held = machine_->held_item())
    for (std::size_t n = 0; n < containers_.size(); ++n)
      if (containers_[n].body == *held) release(n);
  if (trucks_) trucks_->step(kStep_s, containers_, machine_->held_item(), machine_->attachment_bottom_z_m());
  if (bulk_) step_bulk();
  world_->step(kStep_s);
  if (world_->diverged()) {
    warnings_.raise(core::Warning::kNonFinite);
    return;
  }
  clock_.advance();
  events_.impacts.clear();
  events_.twistlocks.clear();
  events_.ropes.clear();
  world_->drain_impacts(events_.impacts);
  machine_->drain_events(events_);
  for (const physics::ImpactEvent& impact : events_.impacts)
    knocks_[static_cast<std::size_t>(knocks_total_++ % scene::kMaxKnocks)] = {
        clock_.steps(), impact.impulse_ns, impact.normal_speed_mps, impact.point};
  update_cab_cues();
  if (!std::isfinite(machine_->attachment_bottom_z_m())) warnings_.raise(core::Warning::kNonFinite);
  for (int n = world_->take_solver_messages(); n > 0; --n)
    warnings_.raise(core::Warning::kSolverMessage);
}

bulk::CarrierMotion Simulation::vessel_motion() const {
  if (!vessel_) return {};
  // the body's velocity is its origin's (the waterline centre); the grids want the frame origin's
  const core::Vec3& w = vessel_->angular_velocity();
  return {vessel_->frame(),
          vessel_->velocity() + cross(w, vessel_->frame().position - vessel_->waterline_centre()), w};
}

void Simulation::step_bulk() {
  // the grids move (a rolling hold); the machine's tool presses into the material (penalty forces on its
  // body, compression of the pressed cells) and bites or spills; its load hangs on it; the material flows
  bulk::move_grids(*bulk_, *scenario_.bulk, clock_.time_s(), vessel_motion());
  const BulkTool* tool = bulk_grab_ >= 0 ? machine_->bulk_tool() : nullptr;
  std::array<bulk::GrabCommand, 1> command;
  if (tool) {
    const bulk::ContactResult contact =
        bulk_->contact({world_->pose(tool->body), world_->linear_velocity(tool->body),
                        world_->angular_velocity(tool->body), tool->contact_points_m});
    if (contact.points_in_contact > 0) world_->add_force_at(tool->body, contact.point, contact.force);
    // the bite follows the shells: close (or open) at the rate that brings the model's jaws to theirs; shells
    // opened by less than the teeth's play beyond the model's jaws hold (their jitter on the ropes does not
    // open the bite)
    constexpr double kShellPlay_m = 0.02;
    const double difference = bulk_->grab(bulk_grab_).opening_m - tool->opening_m;
    const double per_step = tool->grab.max_opening_m / tool->grab.closing_time_s * kStep_s;
    const bool in_play = difference <= 0.0 && difference > -kShellPlay_m;
    command[0] = {tool->jaws, tool->jaws_velocity_mps,
                  in_play ? 0.0 : std::clamp(difference / per_step, -1.0, 1.0)};
  }
  bulk_->step(kStep_s,
              tool ? std::span<const bulk::GrabCommand>(command) : std::span<const bulk::GrabCommand>());
  if (tool) machine_->carry_bulk(bulk_->mass_kg(bulk_->grab(bulk_grab_).load_m3));
}

void Simulation::update_cab_cues() {
  // the specific force at the operator's head: its acceleration (by difference over the step) minus gravity
  const core::Vec3 v = world_->point_velocity(machine_->cab_body(), machine_->eye_on_cab_body_m());
  cab_specific_force_ = (v - cab_velocity_) * (1.0 / kStep_s) + core::Vec3{0.0, 0.0, core::kStandardGravity};
  cab_velocity_ = v;
}

void Simulation::step(const scene::Controls& controls) {
  if (!held_) advance(controls);
}

void Simulation::single_step(const scene::Controls& controls) {
  advance(controls);
}

namespace {
// the telemetry every machine publishes after its own indicators (a machine with ropes: how its load hangs
// and what its ropes carry; every machine: its motions' speeds), named for the console's plots
void describe_telemetry(const Telemetry& t, bool roped, std::vector<std::string>& names) {
  if (roped) names.insert(names.end(), {"swing_m", "rope_tension_kn"});
  for (const AxisSpeed& axis : t.axes)
    if (axis.name) names.push_back(std::string(axis.name) + "_speed_mps");
}
}  // namespace

scene::SceneDescription Simulation::scene() const {
  scene::SceneDescription d;
  machine_->describe(d);
  d.machine_entities = static_cast<int>(d.entities.size());
  describe_telemetry(machine_->telemetry(), roped_, d.indicators);
  if (vessel_) d.entities.push_back({"vessel", "vessel." + vessel_->geometry().placement().vessel.name, {}});
  if (ramp_) {
    d.entities.push_back({"stern ramp", "roro.ramp", ramp_->ramp_half_extents_m()});
    d.entities.push_back({"vehicle deck", "roro.deck", ramp_->deck_half_extents_m()});
  }
  for (const GroundMarking& m : scenario_.markings)
    d.entities.push_back({m.name, "marking.bay", {m.half_length_m, m.half_width_m, kMarkingHalfThickness_m}});
  for (std::size_t k = 0; k < scenario_.blocks.size(); ++k)
    d.entities.push_back(
        {"block " + std::to_string(k + 1), "scenery.block", scenario_.blocks[k].half_extents_m});
  if (trucks_)
    for (int k = 0; k < scenario_.trucks.trucks; ++k)
      d.entities.push_back({"truck " + std::to_string(k + 1), "truck", {}});
  for (const ContainerPlacement& c : scenario_.containers)
    d.entities.push_back({c.id,
                          c.kind == ContainerPlacement::Kind::kHatchCover ? "hatch_cover"
                          : c.kind == ContainerPlacement::Kind::kGeneralCargo
                              ? "cargo"
                              : scene::container_look(2.0 * c.half_extents_m.x),
                          c.half_extents_m});
  return d;
}

void Simulation::write_snapshot(scene::Snapshot& s) const {
  s.version = scene::kSnapshotVersion;
  s.step = clock_.steps();
  s.time_s = clock_.time_s();
  s.held = held_;
  s.power_off = power_off_;
  s.awaiting_zero = awaiting_zero_;
  s.emergency_stop = emergency_stop_;
  s.hand_signal = signal_.signal;
  s.hand_signal_at_s = signal_.at_s;
  s.diverged = world_->diverged();
  s.warnings = warnings_.total();
  s.wind_mps = weather_.wind();
  s.time_of_day_h = weather_.time_of_day_h();
  s.visibility_m = weather_.settings().visibility_m;
  s.rain_mm_per_h = weather_.settings().rain_mm_per_h;
  s.cloud_oktas = weather_.settings().cloud_oktas;
  s.day_of_year = weather_.settings().day_of_year;
  s.latitude_deg = weather_.settings().latitude_deg;
  s.sea.swell_count = 0;
  if (vessel_) {
    // the vessel's heave harmonics as beam swell running onto the quay (-x), in phase at its waterline centre
    const VesselPlacement& placement = vessel_->geometry().placement();
    s.sea.water_level_m = placement.keel_midship_m.z + placement.vessel.draught_m;
    s.sea.reference_m = placement.keel_midship_m + core::Vec3{0.0, 0.0, placement.vessel.draught_m};
    for (const Harmonic& h : placement.sea.heave_m) {
      if (s.sea.swell_count == scene::kMaxSwells) break;
      s.sea.swells[static_cast<std::size_t>(s.sea.swell_count++)] = {h.amplitude, h.period_s, h.phase_rad,
                                                                     std::numbers::pi};
    }
  }

  const core::Pose cab = machine_->cab_pose();
  s.cab.pose = cab;
  s.cab.eye_m = machine_->eye_m();
  s.cab.sight = machine_->cab_sight();
  s.cab.specific_force_mps2 = cab.direction_to_local(cab_specific_force_);
  s.cab.angular_velocity_radps = cab.direction_to_local(world_->angular_velocity(machine_->cab_body()));

  s.knocks_total = knocks_total_;
  s.knocks = knocks_;

  s.rope_count = 0;
  s.indicator_count = 0;
  s.drive_count = 0;
  int n = machine_->publish(s, 0);
  // the telemetry, in the order scene() names it
  const Telemetry telemetry = machine_->telemetry();
  const auto indicator = [&](double value) {
    if (s.indicator_count < scene::kMaxIndicators)
      s.indicators[static_cast<std::size_t>(s.indicator_count++)] = value;
  };
  if (roped_) {
    indicator(telemetry.swing_m);
    indicator(telemetry.rope_tension_n / 1000.0);
  }
  for (const AxisSpeed& axis : telemetry.axes)
    if (axis.name) indicator(axis.speed_mps);
  const auto entity = [&](core::Pose pose, std::uint32_t flags) {
    if (n >= scene::kMaxEntities) return;
    s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), flags, pose};
    ++n;
  };
  if (vessel_) entity(vessel_->geometry().pose_at(clock_.time_s()), 0);  // where the step left it
  if (ramp_) {
    entity(ramp_->ramp_pose(), 0);
    entity(ramp_->deck_pose(), 0);
  }
  for (const GroundMarking& m : scenario_.markings) {
    // paint on the ground under its centre, as that ground lies now
    const double ground_z = ramp_ ? ramp_->at(m.centre_m.x, m.centre_m.y).z_m : 0.0;
    entity({core::Mat3::rotation({0, 0, 1}, m.heading_rad),
            {m.centre_m.x, m.centre_m.y, ground_z + kMarkingHalfThickness_m}},
           0);
  }
  for (const StaticBlock& b : scenario_.blocks)
    entity({core::Mat3::identity(), b.position_m}, 0);
  if (trucks_ && trucks_->team()) {
    for (int k = 0; k < scenario_.trucks.trucks; ++k)  // drawn by their own stations
      entity(trucks_->truck_pose(k), scene::Snapshot::kHidden);
  } else if (trucks_) {
    for (int k = 0; k < scenario_.trucks.trucks; ++k)
      entity({core::Mat3::identity(),
              {scenario_.trucks.lane_x_m, trucks_->truck_y(k), scenario_.trucks.chassis_top_m}},
             0);
  }
  const auto held = machine_->held_item();
  // a box on a team truck: to hand over, then the truck's station's to draw
  const auto on_team_truck = [&](std::size_t box) -> std::uint32_t {
    if (!trucks_ || !trucks_->team()) return 0;
    for (int k = 0; k < trucks_->trucks(); ++k)
      if (trucks_->seated_box(k) == static_cast<int>(box))
        return trucks_->is_taken_over(k) ? scene::Snapshot::kHidden : scene::Snapshot::kOnTeamTruck;
    return 0;
  };
  for (std::size_t c = 0; c < containers_.size(); ++c)
    entity(world_->pose(containers_[c].body),
           held == containers_[c].body ? scene::Snapshot::kLocked : on_team_truck(c));
  s.entity_count = n;
}

std::unique_ptr<scene::Snapshot> Simulation::snapshot() const {
  auto s = std::make_unique<scene::Snapshot>();
  write_snapshot(*s);
  return s;
}

std::uint64_t Simulation::state_hash() const {
  core::StateHash hash;
  hash.add(clock_.steps());
  hash.add(world_->state_hash());
  if (scenario_.machine_hashed_by_hand) {
    machine_->hash_into(hash);
  } else {
    core::StateWriter hashing(hash);  // everything the machine saves, so nothing saved goes unchecked
    machine_->save_state(hashing);
  }
  if (bulk_) hash.add(bulk_->state_hash());
  hash.add(weather_.turbulence_mps());
  obstacles_->hash_into(hash);  // (none outside a team session: states hash as they did)
  if (trucks_ && trucks_->team())
    for (int k = 0; k < trucks_->trucks(); ++k) {
      hash.add(trucks_->seated_box(k));
      hash.add(trucks_->is_taken_over(k));
    }
  hash.add(next_event_);
  if (!scenario_.lift_events.empty()) {  // (scenarios without them hash as they did)
    hash.add(first_lift_step_);
    hash.add(next_lift_event_);
  }
  if (instructor_stop_) hash.add(std::uint8_t{1});  // (states before the stop existed hash as they did)
  if (power_off_) hash.add(std::uint8_t{2});        // (and before the power failure)
  if (awaiting_zero_) hash.add(std::uint8_t{3});
  return hash.value();
}

std::vector<std::uint8_t> Simulation::save_state() const {
  core::StateWriter out;
  // (SIM6 only where another member's machine is an obstacle: other states are saved as they were)
  out.section(obstacles_->count() > 0 ? kSimulationSectionV6 : kSimulationSection);
  out.put(clock_.steps());
  out.put(held_);
  out.put(next_event_);
  out.put(warnings_);
  out.put(instructor_stop_);
  out.put(first_lift_step_);
  out.put(next_lift_event_);
  out.put(power_off_);
  out.put(awaiting_zero_);
  out.put(std::vector<std::uint8_t>(secured_.begin(), secured_.end()));
  if (obstacles_->count() > 0) obstacles_->save_sizes(out);
  world_->save_state(out);
  machine_->save_state(out);
  weather_.save_state(out);
  out.put(trucks_ != nullptr);
  if (trucks_) trucks_->save_state(out);
  if (bulk_) bulk_->save_state(out);
  return out.take();
}

void Simulation::restore_state(const std::vector<std::uint8_t>& state) {
  core::StateReader in(state);
  auto section = in.get<std::uint32_t>();
  const bool with_obstacles = section == kSimulationSectionV6;
  if (with_obstacles) section = kSimulationSection;  // its fields and then the obstacles' sizes
  if (section != kSimulationSection && section != kSimulationSectionV4 && section != kSimulationSectionV3 &&
      section != kSimulationSectionV2)
    throw core::StateError("saved state does not match this simulation at its simulation section");
  clock_.reset(in.get<std::int64_t>());
  if (ramp_) ramp_->move_to(clock_.time_s());
  in.get(held_);
  in.get(next_event_);
  if (next_event_ > scenario_.events.size())
    throw core::StateError("saved state is past this scenario's events");
  in.get(warnings_);
  instructor_stop_ = section != kSimulationSectionV2 ? in.get<bool>() : false;
  first_lift_step_ = -1;
  next_lift_event_ = 0;
  if (section == kSimulationSection || section == kSimulationSectionV4) {
    in.get(first_lift_step_);
    in.get(next_lift_event_);
    if (next_lift_event_ > scenario_.lift_events.size() || first_lift_step_ > clock_.steps())
      throw core::StateError("saved state is past this scenario's events from the first lift");
  }
  power_off_ = section == kSimulationSection ? in.get<bool>() : false;
  awaiting_zero_ = section == kSimulationSection ? in.get<bool>() : false;
  std::vector<std::uint8_t> secured;
  in.get(secured, static_cast<std::int64_t>(secured_.size()));
  secured_.assign(secured.begin(), secured.end());
  if (with_obstacles) {
    obstacles_->restore_sizes(in);
  } else if (obstacles_->count() > 0) {
    throw core::StateError("saved state has no team obstacles, this simulation has");
  }
  world_->restore_state(in);
  machine_->restore_state(in);
  weather_.restore_state(in);
  if (in.get<bool>() != (trucks_ != nullptr)) throw core::StateError("saved state has other trucks");
  if (trucks_) trucks_->restore_state(in);
  if (bulk_) bulk_->restore_state(in);
  if (!in.at_end()) throw core::StateError("saved state is longer than this simulation's");
  events_.impacts.clear();
  events_.twistlocks.clear();
  events_.ropes.clear();
  cab_velocity_ = world_->point_velocity(machine_->cab_body(), machine_->eye_on_cab_body_m());
}

}  // namespace harbour::sim
