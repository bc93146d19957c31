#include "harbour/sim/Simulation.h"

#include <cmath>

#include "harbour/core/StateHash.h"

namespace harbour::sim {

Simulation::Simulation(const ScenarioSettings& scenario)
    : scenario_(scenario), weather_(scenario.weather, scenario.seed) {
  world_ = std::make_unique<physics::PhysicsWorld>(physics::WorldSettings{});
  world_->add_ground(0.0);
  for (const StaticBlock& b : scenario.blocks) {
    core::Pose p;
    p.position = b.position_m;
    world_->add_static_box(b.half_extents_m, p);
  }
  for (const ContainerPlacement& c : scenario.containers) {
    physics::BoxSettings box;
    box.half_extents_m = c.half_extents_m;
    box.mass_kg = c.gross_mass_kg;
    box.pose.position = c.position_m;
    box.pose.rotation = core::Mat3::rotation({0, 0, 1}, c.yaw_rad);
    containers_.push_back({world_->add_box(box), c.half_extents_m});
  }
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

void Simulation::apply_wind() {
  // drag on the spreader and on the box it carries
  const core::Vec3 wind = weather_.wind();
  const double rho = scenario_.weather.air_density_kg_m3, cd = scenario_.drag_coefficient;
  const physics::BodyId spreader = crane_->spreader_body();
  const core::Pose sp = world_->pose(spreader);
  world_->add_force_at(spreader, sp.position,
                       box_drag(wind, world_->linear_velocity(spreader), sp,
                                scenario_.crane.spreader_half_extents_m, cd, rho));
  if (const auto box = crane_->locked_container()) {
    for (const ContainerRef& c : containers_) {
      if (c.body != *box) continue;
      const core::Pose p = world_->pose(c.body);
      world_->add_force_at(c.body, p.position,
                           box_drag(wind, world_->linear_velocity(c.body), p, c.half_extents_m, cd, rho));
    }
  }
}

void Simulation::advance(const Inputs& inputs) {
  // scripted events, weather and wind, the machine (drives, ropes, twistlocks) pushing on the bodies, then
  // the multibody step
  apply_due_events();
  weather_.step(kStep_s);
  apply_wind();
  crane_->step(inputs.sts, containers_, kStep_s);
  world_->step(kStep_s);
  clock_.advance();
  events_.impacts = world_->take_impacts();
  events_.twistlocks = crane_->take_twistlock_events();
  events_.ropes = crane_->hoist().take_events();
  const core::Vec3 p = crane_->spreader_pose().position;
  if (!std::isfinite(p.x + p.y + p.z)) warnings_.raise(core::Warning::kNonFinite);
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
  s.spreader = crane_->spreader_pose();
  s.lamps = crane_->lamps();
  s.hoisted_load_n = crane_->hoisted_load_n();
  s.warnings = warnings_.total();
  s.wind_mps = weather_.wind();
  s.time_of_day_h = weather_.time_of_day_h();
  s.visibility_m = scenario_.weather.visibility_m;
  s.rain_mm_per_h = scenario_.weather.rain_mm_per_h;
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
  hash.add(weather_.turbulence_mps());
  hash.add(next_event_);
  return hash.value();
}

}  // namespace harbour::sim
