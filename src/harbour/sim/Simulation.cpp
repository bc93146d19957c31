#include "harbour/sim/Simulation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "harbour/core/StateHash.h"

namespace harbour::sim {

Simulation::Simulation(const ScenarioSettings& scenario)
    : scenario_(scenario), weather_(scenario.weather, scenario.seed) {
  world_ = std::make_unique<physics::PhysicsWorld>(physics::WorldSettings{});
  if (scenario.vessel) {
    // the quay apron up to its edge, the harbour bed under the water
    constexpr double kQuayDepth_m = 20.0, kQuayLand_m = 500.0;
    world_->add_static_box(
        {kQuayLand_m / 2, kQuayLand_m, kQuayDepth_m / 2},
        {core::Mat3::identity(), {scenario.quay_edge_x_m - kQuayLand_m / 2, 0.0, -kQuayDepth_m / 2}},
        kSurfaceQuay);
    world_->add_ground(-kQuayDepth_m, kSurfaceGround);
    vessel_ = std::make_unique<Vessel>(*world_, *scenario.vessel);
  } else {
    world_->add_ground(0.0, kSurfaceQuay);
  }
  for (const StaticBlock& b : scenario.blocks) {
    core::Pose p;
    p.position = b.position_m;
    world_->add_static_box(b.half_extents_m, p, kSurfaceQuay);
  }
  for (const ContainerPlacement& c : scenario.containers) {
    physics::BoxSettings box;
    box.half_extents_m = c.half_extents_m;
    box.mass_kg = c.gross_mass_kg;
    box.pose = c.pose;
    box.center_of_mass_m = c.center_of_mass_m;
    box.surface = c.kind == ContainerPlacement::Kind::kHatchCover ? kSurfaceHatchCover : kSurfaceContainer;
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
  crane_ = std::make_unique<StsCrane>(*world_, scenario.crane, scenario.gantry_y_m, scenario.trolley_x_m,
                                      scenario.spreader_z_m);
}

void Simulation::apply_due_events() {
  while (next_event_ < scenario_.events.size() && scenario_.events[next_event_].at_s <= clock_.time_s()) {
    const ScriptedEvent& e = scenario_.events[next_event_++];
    switch (e.kind) {
      case ScriptedEvent::Kind::kGust: {
        Gust g = e.gust;
        g.start_s = e.at_s;
        weather_.add_gust(g);
        break;
      }
      case ScriptedEvent::Kind::kHoistBrakeFault:
        crane_->set_hoist_brake_fault(true);
        break;
      case ScriptedEvent::Kind::kLandedSensorFault:
        crane_->set_landed_sensor_fault(e.corner);
        break;
    }
  }
}

std::string why_invalid(const InstructorCommand& c) {
  using Kind = InstructorCommand::Kind;
  switch (c.kind) {
    case Kind::kGust:
      if (!(c.gust.duration_s > 0.0 && c.gust.duration_s <= 600.0 && c.gust.amplitude_mps > 0.0 &&
            c.gust.amplitude_mps <= kMaxGust_mps))
        return "a gust lasts up to 600 s and peaks at 0-" + std::to_string(static_cast<int>(kMaxGust_mps)) +
               " m/s over the mean";
      break;
    case Kind::kLandedSensorFault:
      if (c.corner < 0 || c.corner > 3) return "a twistlock corner is 0-3";
      break;
    case Kind::kSetWind:
      if (!(c.wind_mean_mps >= 0.0 && c.wind_mean_mps <= kMaxMeanWind_mps && c.turbulence >= 0.0 &&
            c.turbulence <= 1.0 && c.wind_from_rad >= 0.0 && c.wind_from_rad <= 2.0 * std::numbers::pi))
        return "wind 0-" + std::to_string(static_cast<int>(kMaxMeanWind_mps)) +
               " m/s from 0-360 deg, turbulence intensity 0-1";
      break;
    case Kind::kSetVisibility:
      if (!(c.value > 0.0 && c.value <= 1e5)) return "visibility 0-100 km";
      break;
    case Kind::kSetRain:
      if (!(c.value >= 0.0 && c.value <= 500.0)) return "rain 0-500 mm/h";
      break;
    case Kind::kSetTimeOfDay:
      if (!(c.value >= 0.0 && c.value < 24.0)) return "time of day 0-24 h";
      break;
    case Kind::kHoistBrakeFault:
    case Kind::kClearFaults:
      break;
    default:
      return "unknown command kind " + std::to_string(static_cast<int>(c.kind));
  }
  return {};
}

void Simulation::command(const InstructorCommand& c) {
  using Kind = InstructorCommand::Kind;
  if (const std::string why = why_invalid(c); !why.empty())
    throw std::invalid_argument("instructor command: " + why);
  switch (c.kind) {
    case Kind::kGust: {
      Gust g = c.gust;
      g.start_s = clock_.time_s();
      weather_.add_gust(g);
      break;
    }
    case Kind::kHoistBrakeFault:
      crane_->set_hoist_brake_fault(true);
      break;
    case Kind::kLandedSensorFault:
      crane_->set_landed_sensor_fault(c.corner);
      break;
    case Kind::kClearFaults:
      crane_->set_hoist_brake_fault(false);
      crane_->set_landed_sensor_fault(-1);
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
    case Kind::kSetTimeOfDay:
      weather_.set_time_of_day(c.value);
      break;
  }
}

void Simulation::apply_wind() {
  // drag on the spreader and on the box it carries
  const core::Vec3 wind = weather_.wind();
  const double rho = scenario_.weather.air_density_kg_m3, cd = scenario_.drag_coefficient;
  const physics::BodyId spreader = crane_->spreader_body();
  const core::Pose sp = world_->pose(spreader);
  world_->add_force_at(
      spreader, sp.position,
      box_drag(wind, world_->linear_velocity(spreader), sp, crane_->spreader_half_extents_m(), cd, rho));
  if (const auto box = crane_->locked_container()) {
    for (const ContainerRef& c : containers_) {
      if (c.body != *box) continue;
      const core::Pose p = world_->pose(c.body);
      world_->add_force_at(c.body, p.position,
                           box_drag(wind, world_->linear_velocity(c.body), p, c.half_extents_m, cd, rho));
    }
  }
}

core::Vec3 Simulation::wind_rest_offset_m(const core::Vec3& wind, std::optional<physics::BodyId> box) const {
  const double rho = scenario_.weather.air_density_kg_m3, cd = scenario_.drag_coefficient;
  const physics::BodyId spreader = crane_->spreader_body();
  core::Vec3 force = box_drag(wind, {}, world_->pose(spreader), crane_->spreader_half_extents_m(), cd, rho);
  double mass_kg = world_->mass_kg(spreader);
  for (const ContainerRef& c : containers_)
    if (box && c.body == *box) {
      force += box_drag(wind, {}, world_->pose(c.body), c.half_extents_m, cd, rho);
      mass_kg += world_->mass_kg(c.body);
    }
  const double lean = crane_->pendulum_length_m() / (mass_kg * 9.80665);
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

void Simulation::advance(const Inputs& inputs) {
  if (world_->diverged()) return;  // stopped where it diverged
  // scripted events, weather and wind, the machine (drives, ropes, twistlocks) pushing on the bodies, then
  // the multibody step
  apply_due_events();
  weather_.step(kStep_s);
  apply_wind();
  if (vessel_) vessel_->move_to(clock_.time_s());
  move_secured_cargo();
  crane_->step(in_range(inputs).sts, containers_, kStep_s);
  if (const auto locked = crane_->locked_container())
    for (std::size_t n = 0; n < containers_.size(); ++n)
      if (containers_[n].body == *locked) release(n);
  if (trucks_) trucks_->step(kStep_s, containers_, *crane_);
  world_->step(kStep_s);
  if (world_->diverged()) {
    warnings_.raise(core::Warning::kNonFinite);
    return;
  }
  clock_.advance();
  events_.impacts = world_->take_impacts();
  events_.twistlocks = crane_->take_twistlock_events();
  events_.ropes = crane_->hoist().take_events();
  const core::Vec3 p = crane_->spreader_pose().position;
  if (!std::isfinite(p.x + p.y + p.z)) warnings_.raise(core::Warning::kNonFinite);
  for (int n = world_->take_solver_messages(); n > 0; --n)
    warnings_.raise(core::Warning::kSolverMessage);
}

Inputs in_range(const Inputs& inputs) {
  const auto lever = [](double v) { return std::isfinite(v) ? std::clamp(v, -1.0, 1.0) : 0.0; };
  Inputs r = inputs;
  r.sts.gantry = lever(r.sts.gantry);
  r.sts.trolley = lever(r.sts.trolley);
  r.sts.hoist = lever(r.sts.hoist);
  r.sts.boom = lever(r.sts.boom);
  const auto size = r.sts.spreader_size_ft;
  if (size != 20 && size != 40 && size != 45) r.sts.spreader_size_ft = 0;
  return r;
}

void Simulation::step(const Inputs& inputs) {
  if (!held_) advance(inputs);
}

void Simulation::single_step(const Inputs& inputs) {
  advance(inputs);
}

Snapshot Simulation::snapshot() const {
  Snapshot s;
  s.step = clock_.steps();
  s.time_s = clock_.time_s();
  s.held = held_;
  s.gantry_y_m = crane_->gantry_position_m();
  s.trolley_x_m = crane_->trolley_position_m();
  s.boom_angle_rad = crane_->boom_angle_rad();
  s.spreader = crane_->spreader_pose();
  s.spreader_frame = crane_->spreader_state();
  s.lamps = crane_->lamps();
  s.horn = crane_->horn();
  s.hoisted_load_n = crane_->hoisted_load_n();
  s.warnings = warnings_.total();
  s.wind_mps = weather_.wind();
  s.time_of_day_h = weather_.time_of_day_h();
  s.visibility_m = weather_.settings().visibility_m;
  s.rain_mm_per_h = weather_.settings().rain_mm_per_h;
  if (vessel_) s.vessel = vessel_->geometry().pose_at(clock_.time_s());  // where the step left it
  if (trucks_)
    for (int k = 0; k < scenario_.trucks.trucks; ++k)
      s.trucks.push_back({core::Mat3::identity(),
                          {scenario_.trucks.lane_x_m, trucks_->truck_y(k), scenario_.trucks.chassis_top_m}});
  for (std::size_t n = 0; n < containers_.size(); ++n)
    s.containers.push_back({scenario_.containers[n].id, world_->pose(containers_[n].body),
                            crane_->locked_container() == containers_[n].body});
  return s;
}

std::uint64_t Simulation::state_hash() const {
  core::StateHash hash;
  hash.add(clock_.steps());
  hash.add(world_->state_hash());
  crane_->hoist().hash_into(hash);
  hash.add(crane_->gantry_drive().reference_mps());
  hash.add(crane_->trolley_drive().reference_mps());
  hash.add(crane_->lamps());
  hash.add(crane_->boom_angle_rad());
  const SpreaderState spreader = crane_->spreader_state();
  hash.add(spreader.length_m);
  hash.add(spreader.flippers);
  hash.add(weather_.turbulence_mps());
  hash.add(next_event_);
  return hash.value();
}

std::vector<std::uint8_t> Simulation::save_state() const {
  core::StateWriter out;
  out.section(0x53494D32);  // "SIM2": with solver-message warnings
  out.put(clock_.steps());
  out.put(held_);
  out.put(next_event_);
  out.put(warnings_);
  out.put(std::vector<std::uint8_t>(secured_.begin(), secured_.end()));
  world_->save_state(out);
  crane_->save_state(out);
  weather_.save_state(out);
  out.put(trucks_ != nullptr);
  if (trucks_) trucks_->save_state(out);
  return out.take();
}

void Simulation::restore_state(const std::vector<std::uint8_t>& state) {
  core::StateReader in(state);
  in.section(0x53494D32, "simulation");
  clock_.reset(in.get<std::int64_t>());
  in.get(held_);
  in.get(next_event_);
  if (next_event_ > scenario_.events.size())
    throw core::StateError("saved state is past this scenario's events");
  in.get(warnings_);
  std::vector<std::uint8_t> secured;
  in.get(secured, static_cast<std::int64_t>(secured_.size()));
  secured_.assign(secured.begin(), secured.end());
  world_->restore_state(in);
  crane_->restore_state(in);
  weather_.restore_state(in);
  if (in.get<bool>() != (trucks_ != nullptr)) throw core::StateError("saved state has other trucks");
  if (trucks_) trucks_->restore_state(in);
  if (!in.at_end()) throw core::StateError("saved state is longer than this simulation's");
  events_ = {};
}

}  // namespace harbour::sim
