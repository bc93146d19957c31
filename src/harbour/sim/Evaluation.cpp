#include "harbour/sim/Evaluation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "harbour/bulk/PileMeasure.h"
#include "harbour/scene/HandSignals.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

// a grab letting go of this share of its capacity at once opened to discharge
constexpr double kReleasedShare = 0.05;
constexpr double kAxisSample_s = 0.1;   // the motions' speeds sampled this often for their jerk
constexpr double kMoving_mps = 0.05;    // a motion slower than this (now and at the last sample) stands
constexpr double kPileMeasure_s = 0.5;  // a trimmed pile's top measured this often

}  // namespace

const char* skill_name(Skill skill) {
  switch (skill) {
    case Skill::kSafety:
      return "safety";
    case Skill::kPrecision:
      return "precision";
    case Skill::kProductivity:
      return "productivity";
  }
  return "?";
}

void reserve_lists(Metrics& metrics) {
  constexpr std::size_t kRoom = 256;  // moves, landings, bites, signals: a long attempt's worth
  for (std::vector<double>* list :
       {&metrics.cycle_times_s, &metrics.landing_sway_m, &metrics.bite_fill, &metrics.release_swing_m,
        &metrics.placement_offset_m, &metrics.placement_skew_deg, &metrics.signal_delays_s})
    list->reserve(std::max(kRoom, list->size()));
}

const char* outcome_name(Outcome outcome) {
  switch (outcome) {
    case Outcome::kPassed:
      return "passed";
    case Outcome::kFailed:
      return "failed";
    case Outcome::kEndedByInstructor:
      return "ended by the instructor";
  }
  return "?";
}

bool scripts_fault(const ExerciseSettings& exercise, MachineFault fault) {
  const auto kind_of = [](ScriptedEvent::Kind kind) -> std::optional<MachineFault> {
    switch (kind) {
      case ScriptedEvent::Kind::kHoistBrakeFault:
        return MachineFault::kHoistBrake;
      case ScriptedEvent::Kind::kLandedSensorFault:
        return MachineFault::kLandedSensor;
      case ScriptedEvent::Kind::kLimiterFault:
        return MachineFault::kLoadMomentLimiter;
      case ScriptedEvent::Kind::kGust:
        return std::nullopt;
    }
    return std::nullopt;
  };
  for (const auto* events : {&exercise.scenario.events, &exercise.scenario.lift_events})
    for (const ScriptedEvent& e : *events)
      if (kind_of(e.kind) == fault) return true;
  return false;
}

Evaluator::Evaluator(const ExerciseSettings& exercise)
    : exercise_(exercise), done_(exercise.moves.size(), false) {
  if (exercise.scenario.machine.has_value()) metrics_.machine = &exercise.scenario.machine.type();
  reserve_lists(metrics_);  // a station evaluates on its step thread, which must not allocate
}

int Evaluator::goal_of(physics::BodyId body, const Simulation& simulation) const {
  for (std::size_t g = 0; g < exercise_.moves.size(); ++g) {
    for (std::size_t c = 0; c < simulation.scenario().containers.size(); ++c)
      if (simulation.scenario().containers[c].id == exercise_.moves[g].container_id &&
          simulation.container_body(c) == body)
        return static_cast<int>(g);
    for (const auto& [id, item] : simulation.machine().own_items())
      if (id == exercise_.moves[g].container_id && item == body) return static_cast<int>(g);
  }
  return -1;
}

std::optional<core::Vec3> move_target(const MoveGoal& goal, const Simulation& simulation) {
  if (!goal.to_truck || !simulation.trucks() || !simulation.trucks()->team()) return goal.target_m;
  const double height_m = 2.0 * (goal.target_m.z - simulation.scenario().trucks.chassis_top_m);
  return simulation.trucks()->load_centre(height_m);
}

bool Evaluator::near_target(physics::BodyId box, const Simulation& simulation) const {
  const int g = goal_of(box, simulation);
  if (g < 0) return false;
  const core::Vec3 p = simulation.world().pose(box).position;
  const std::optional<core::Vec3> t = move_target(exercise_.moves[g], simulation);
  return t && std::hypot(p.x - t->x, p.y - t->y) <= 2.0 * exercise_.moves[g].tolerance_m;
}

void Evaluator::record_landing(const Simulation& simulation, std::optional<physics::BodyId> hanging_box) {
  const double sway = sway_m(simulation, hanging_box);
  metrics_.landing_sway_m.push_back(sway);
  if (sway > exercise_.rules.sway_limit_m) ++metrics_.sway_landings;
}

double Evaluator::sway_m(const Simulation& simulation, std::optional<physics::BodyId> hanging_box) const {
  // the hanging tool's horizontal offset from where it hangs at rest: plumb under its sheaves, moved
  // downwind by the mean wind (a steady lean is not a swing; the turbulence's and gusts' pushes are)
  const core::Vec3 swing = simulation.machine().tally().swing_m;  // horizontal (z 0), as the rest
  return core::length(swing - simulation.wind_rest_offset_m(simulation.weather().mean_wind(), hanging_box));
}

void Evaluator::count_collision(const physics::ImpactEvent& e) {
  ++metrics_.collisions;
  metrics_.worst_collision_mps = std::max(metrics_.worst_collision_mps, e.normal_speed_mps);
  metrics_.collision_impulse_ns += e.impulse_ns;
  metrics_.worst_collision_impulse_ns = std::max(metrics_.worst_collision_impulse_ns, e.impulse_ns);
  auto either = [&](int surface) { return e.surface == surface || e.other_surface == surface; };
  auto box_or_spreader = [](int s) {
    return s == scene::kSurfaceContainer || s == scene::kSurfaceHatchCover || s == scene::kSurfaceSpreader ||
           s == scene::kSurfaceFlipper;
  };
  if (either(scene::kSurfaceCellGuide)) {
    ++metrics_.cell_guide_collisions;
  } else if (either(scene::kSurfaceHull)) {
    ++metrics_.ship_collisions;
  } else if ((box_or_spreader(e.surface) && box_or_spreader(e.other_surface)) ||
             (either(scene::kSurfaceVehicle) &&
              (either(scene::kSurfaceContainer) || either(scene::kSurfaceHatchCover)))) {
    ++metrics_.container_collisions;  // a stack hit by the spreader, a box or a vehicle
  } else if (either(scene::kSurfaceTruck) || either(scene::kSurfaceVehicle)) {
    ++metrics_.vehicle_collisions;
  } else {
    ++metrics_.other_collisions;
  }
}

void Evaluator::observe(const Simulation& simulation, const scene::Controls& controls) {
  metrics_.time_s = simulation.time_s();
  const int stop = simulation.control_table().find("emergency_stop");
  // read as the machine reads it (a non-finite value, a device fault, reads released)
  const bool estop =
      stop >= 0 && simulation.control_table().in_range(controls).value[static_cast<std::size_t>(stop)] != 0.0;
  const MachineTally tally = simulation.machine().tally();
  observe_hoist_fault(simulation, estop);
  observe_instructor(simulation);
  observe_signals(simulation, controls);
  observe_machine(simulation, controls, tally, estop);
  if (simulation.bulk()) observe_bulk(simulation, tally);
  observe_smoothness(simulation, tally);
  observe_speed_zones(simulation);
  metrics_.vehicle = tally.vehicle;
  metrics_.jackknifes = static_cast<int>(tally.jackknifes);
  metrics_.tip_overs = static_cast<int>(tally.tip_overs);
  metrics_.limiter_trips = static_cast<int>(tally.limiter_trips);
  metrics_.pad_lift_offs = static_cast<int>(tally.pad_lift_offs);
  if (const TruckLane* trucks = simulation.trucks(); trucks && trucks->team()) {
    int taken_over = 0, set_on_trucks = 0;
    for (int k = 0; k < trucks->trucks(); ++k)
      taken_over += trucks->is_taken_over(k) ? 1 : 0;
    for (std::size_t g = 0; g < exercise_.moves.size(); ++g)
      set_on_trucks += done_[g] && exercise_.moves[g].to_truck ? 1 : 0;
    hand_offs_pending_ = std::max(0, set_on_trucks - taken_over);
  }
}

void Evaluator::observe_instructor(const Simulation& simulation) {
  // what the instructor did to the machine that the exercise does not script: a fault, a stop, the supply cut
  bool disrupted = simulation.instructor_stopped() || simulation.power_off();
  for (const MachineFault fault :
       {MachineFault::kHoistBrake, MachineFault::kLandedSensor, MachineFault::kLoadMomentLimiter})
    disrupted = disrupted || (simulation.machine().fault_active(fault) && !scripts_fault(exercise_, fault));
  if (disrupted && !disrupted_) ++metrics_.instructor_disruptions;
  disrupted_ = disrupted;
}

void Evaluator::observe_signals(const Simulation& simulation, const scene::Controls& controls) {
  const Simulation::GivenSignal& given = simulation.signal();
  if (given.count != signals_seen_) {  // a new signal replaces the last (late only if its time had passed)
    signals_seen_ = given.count;
    ++metrics_.signals;
    signal_pending_ = true;
    signal_late_ = false;
  }
  if (!signal_pending_) return;
  const scene::HandSignal& signal = scene::hand_signals()[static_cast<std::size_t>(given.signal)];
  const double waited_s = simulation.time_s() - given.at_s;
  if (scene::follows(signal, simulation.control_table(), controls)) {
    metrics_.signal_delays_s.push_back(waited_s);
    signal_pending_ = false;
  }
  if (signal_pending_ && !signal_late_ && waited_s > exercise_.rules.signal_reaction_s) {
    signal_late_ = true;
    ++metrics_.late_signals;
    if (signal.sense == 0) ++metrics_.late_stop_signals;
  }
}

void Evaluator::observe_hoist_fault(const Simulation& simulation, bool emergency_stop) {
  const Machine& machine = simulation.machine();
  // falling: the attachment sinking faster than any hoist lowers, over 0.1 s (contact jitter is not a fall),
  // with its hoist paying rope out that fast (a drum running free): sinking back along a swing's arc or onto
  // ropes gone slack turns no drum, and a free drum spooling rope onto a set-down attachment sinks nothing
  if (simulation.time_s() + 1e-9 >= next_drop_sample_s_) {
    const double z = machine.attachment_bottom_z_m(), fall = exercise_.rules.load_drop_mps;
    if (drop_primed_) {
      const bool falling =
          (drop_sample_z_m_ - z) / kAxisSample_s > fall && machine.lowering_speed_mps() > fall;
      if (falling && !dropping_) ++metrics_.load_drops;
      dropping_ = falling;
    }
    drop_sample_z_m_ = z;
    drop_primed_ = true;
    next_drop_sample_s_ = simulation.time_s() + kAxisSample_s;
  }
  // the hoist brake fault's procedure: the load landed under power, nothing lifted again, the machine stopped
  const bool suspended = simulation.carrying();
  const bool fault = machine.fault_active(MachineFault::kHoistBrake);
  if (fault) {
    if (!metrics_.hoist_fault && suspended) fault_since_s_ = metrics_.time_s;
    metrics_.hoist_fault = true;
    if (suspended && !suspended_) ++metrics_.lifts_under_fault;
    if (!suspended && suspended_ && fault_since_s_ >= 0.0 && metrics_.fault_set_down_s < 0.0)
      metrics_.fault_set_down_s = metrics_.time_s - fault_since_s_;
  }
  stopping_safely_ = fault && !suspended;
  if (stopping_safely_ && emergency_stop) metrics_.stopped_after_fault = true;
  suspended_ = suspended;
}

void Evaluator::observe_speed_zones(const Simulation& simulation) {
  // the cab's ground speed in the zone it is in: each onset of a speed over the zone's limit
  if (exercise_.speed_zones.empty()) return;
  const physics::BodyId cab = simulation.machine().cab_body();
  const core::Vec3 p = simulation.world().pose(cab).position, v = simulation.world().linear_velocity(cab);
  const double kmh = std::hypot(v.x, v.y) * 3.6;
  double over = -1e9;
  for (const SpeedZone& z : exercise_.speed_zones)
    if (p.x >= z.min_x_m && p.x <= z.max_x_m && p.y >= z.min_y_m && p.y <= z.max_y_m)
      over = std::max(over, kmh - z.limit_kmh);
  metrics_.worst_overspeed_kmh = std::max(metrics_.worst_overspeed_kmh, over);
  const bool speeding = over > exercise_.rules.overspeed_margin_kmh;
  if (speeding && !speeding_) ++metrics_.overspeeds;
  speeding_ = over > 0.0 && (speeding || speeding_);  // until back within the limit
}

void Evaluator::observe_smoothness(const Simulation& simulation, const MachineTally& tally) {
  // every 0.1 s: each named motion's acceleration and jerk by differences of its speed; the jerk's RMS while
  // it moves, and each onset of a jerk above the rules' limit (a lever slammed, a move stopped short)
  if (simulation.time_s() + 1e-9 < next_axis_sample_s_) return;
  next_axis_sample_s_ = simulation.time_s() + kAxisSample_s;
  for (std::size_t n = 0; n < tally.axes.size() && tally.axes[n].name; ++n) {
    if (n >= axes_.size()) {
      axes_.push_back({});
      metrics_.smoothness.push_back({tally.axes[n].name});
    }
    AxisTrack& a = axes_[n];
    const double v = tally.axes[n].speed_mps;
    const double acceleration = (v - a.speed_mps) / kAxisSample_s;
    const double jerk = (acceleration - a.acceleration_mps2) / kAxisSample_s;
    const bool moving = std::abs(v) > kMoving_mps || std::abs(a.speed_mps) > kMoving_mps;
    if (a.samples >= 2 && moving) {
      a.jerk_squares += jerk * jerk;
      ++a.moving_samples;
      const bool harsh = std::abs(jerk) > exercise_.rules.harsh_jerk_mps3;
      if (harsh && !a.harsh) ++metrics_.smoothness[n].harsh_moves;
      a.harsh = harsh;
    }
    ++a.samples;
    a.speed_mps = v;
    a.acceleration_mps2 = acceleration;
    if (a.moving_samples > 0)
      metrics_.smoothness[n].rms_jerk_mps3 = std::sqrt(a.jerk_squares / a.moving_samples);
  }
}

bool Evaluator::goals_met() const {
  return metrics_.moves_completed == static_cast<int>(exercise_.moves.size()) &&
         (!exercise_.deliver || metrics_.delivered_t >= exercise_.deliver->tonnes) &&
         (!exercise_.trim || trimmed_);
}

bool Evaluator::finished() const {
  // (a box set on a team's truck ends the crane's part only once that truck's station has taken it over)
  return metrics_.stopped_after_fault || ((!exercise_.moves.empty() || exercise_.deliver || exercise_.trim) &&
                                          goals_met() && hand_offs_pending_ == 0);
}

double pile_top_m(const bulk::BulkWorld& bulk, int grid) {
  const bulk::HeightGrid& g = bulk.grid(grid);
  const bulk::CellIndex top = bulk::highest_cell(g);
  const core::Vec3 centre = g.cell_centre(top.i, top.j);
  return g.pose().to_parent({centre.x, centre.y, g.height(top.i, top.j)}).z;
}

void Evaluator::observe_bulk(const Simulation& simulation, const MachineTally& tally) {
  // tonnes delivered, handled and spilled; each bite's fill as the grab starts to discharge it, and the
  // grab's swing then
  const bulk::BulkWorld& bulk = *simulation.bulk();
  const double t_per_m3 = bulk.material().bulk_density_kg_m3 / 1000.0;
  metrics_.bulk = true;
  if (exercise_.deliver) metrics_.delivered_t = bulk.landed_m3(exercise_.deliver->grid_index) * t_per_m3;
  metrics_.handled_t = bulk.unloaded_m3() * t_per_m3;
  metrics_.spilled_t = bulk.spilled_m3() * t_per_m3;
  metrics_.spilled_percent = metrics_.handled_t > 0 ? 100.0 * metrics_.spilled_t / metrics_.handled_t : 0.0;
  metrics_.tonnes_per_hour = metrics_.time_s > 0 ? metrics_.delivered_t * 3600.0 / metrics_.time_s : 0.0;
  if (exercise_.trim && simulation.time_s() + 1e-9 >= next_pile_measure_s_) {
    // trimmed once the top is down with the material moved: nothing in the grab or on its way down
    metrics_.trim = true;
    metrics_.pile_top_m = pile_top_m(bulk, exercise_.trim->grid_index);
    const bool placed = bulk.parcels().empty() &&
                        (simulation.bulk_grab() < 0 || bulk.grab(simulation.bulk_grab()).load_m3 <= 0.0);
    trimmed_ = placed && metrics_.pile_top_m <= exercise_.trim->top_m;
    next_pile_measure_s_ = simulation.time_s() + kPileMeasure_s;
  }
  if (simulation.bulk_grab() < 0) return;
  const double load = bulk.grab(simulation.bulk_grab()).load_m3;
  // it opened: the bite is what it held (a shell's jitter while it digs lets a little go, not a release)
  const double capacity = bulk.grab_settings(simulation.bulk_grab()).capacity_m3;
  if (!discharging_ && load < bite_peak_m3_ - kReleasedShare * capacity) {
    const double fill = bite_peak_m3_ / capacity;
    metrics_.bite_fill.push_back(fill);
    if (fill < exercise_.rules.poor_bite_fill) ++metrics_.poor_bites;
    const double swing_m = core::length(tally.swing_m);
    metrics_.release_swing_m.push_back(swing_m);
    if (swing_m > exercise_.rules.sway_limit_m) ++metrics_.swinging_releases;
    discharging_ = true;
  }
  if (load <= 0.0) discharging_ = false, bite_peak_m3_ = 0.0;
  if (!discharging_) bite_peak_m3_ = std::max(bite_peak_m3_, load);
}

void Evaluator::observe_machine(const Simulation& simulation, const scene::Controls& controls,
                                const MachineTally& tally, bool estop) {
  // impacts: the load it carries set down near its target, or its empty gripper set down on the item it is
  // to pick up or, after a hoist brake fault, to stay, is a landing; a harder one elsewhere a collision
  const std::optional<physics::BodyId> gripper = simulation.machine().gripper_body();
  for (const physics::ImpactEvent& e : simulation.events().impacts) {
    const bool carried_hit = carried_ && (e.body == *carried_ || e.other == *carried_);
    const bool gripper_hit = gripper && (e.body == *gripper || e.other == *gripper);
    const bool body_hit = e.surface == scene::kSurfaceVehicle || e.other_surface == scene::kSurfaceVehicle;
    if (gripper_hit && carried_hit)
      continue;  // a knock on the item it holds (a bounce as it locks): one body
    if (!gripper_hit && !carried_hit && !body_hit)
      continue;  // two other things meeting (a truck driving off with its box): not the machine's doing
    const physics::BodyId other = e.body == gripper ? e.other : e.body;
    // set down on the item to lift, or (the hoist brake failed, the load down) set down to stay
    if (gripper_hit && !carried_ && (goal_of(other, simulation) >= 0 || stopping_safely_)) {
      metrics_.worst_landing_mps = std::max(metrics_.worst_landing_mps, e.normal_speed_mps);
      if (e.normal_speed_mps > exercise_.rules.hard_landing_mps) ++metrics_.hard_landings;
      continue;
    }
    if (carried_hit && near_target(*carried_, simulation)) {
      record_landing(simulation, carried_);
      metrics_.worst_landing_mps = std::max(metrics_.worst_landing_mps, e.normal_speed_mps);
      if (e.normal_speed_mps > exercise_.rules.hard_landing_mps) ++metrics_.hard_landings;
    } else if (e.normal_speed_mps >= exercise_.rules.collision_speed_mps ||
               (body_hit && e.impulse_ns >= exercise_.rules.body_contact_impulse_ns)) {
      count_collision(e);
    }
  }
  const std::optional<physics::BodyId> held = simulation.machine().held_item();
  observe_moves(simulation, held);
  if (!carried_ && held) record_landing(simulation, std::nullopt);  // picked up: landed and locked on
  carried_ = held;
  metrics_.twistlock_misuse += static_cast<int>(simulation.events().twistlocks.size());
  for (const cable::CableEvent& e : simulation.events().ropes)
    if (e.kind == cable::CableEventKind::kOverload) ++metrics_.overloads;
  if (estop && !was_estop_ && !stopping_safely_) ++metrics_.emergency_stops;
  was_estop_ = estop;
  metrics_.limit_hits += static_cast<int>(tally.limit_hits - limit_hits_seen_);
  limit_hits_seen_ = tally.limit_hits;
  metrics_.hoist_energy_j += tally.hoist_power_w * Simulation::kStep_s;
  metrics_.travel_energy_j += tally.travel_power_w * Simulation::kStep_s;
  if (tally.warns_before_travel) {
    const int horn = simulation.control_table().find("horn");
    observe_gantry_warning(horn >= 0 && controls.value[static_cast<std::size_t>(horn)] != 0.0,
                           tally.travelling, tally.travel_position_m);
  }
}

void Evaluator::observe_moves(const Simulation& simulation, std::optional<physics::BodyId> held) {
  // moves: a goal item held (locked to the spreader, slung to the hook), then let go of at its target
  if (carried_ && !held) {
    const int g = goal_of(*carried_, simulation);
    if (g >= 0 && !done_[g]) {
      const MoveGoal& goal = exercise_.moves[g];
      const core::Pose pose = simulation.world().pose(*carried_);
      // (a team truck that has just left with it: its box is where it was set down)
      const core::Vec3 p = pose.position, t = move_target(goal, simulation).value_or(p);
      const double offset = std::hypot(p.x - t.x, p.y - t.y);
      // skew: its heading from the goal's, a box's either way round
      double skew = 0.0;
      if (goal.heading_rad) {
        const core::Vec3 x = pose.rotation.column(0);
        const double period = goal.on_wheels ? 2.0 * std::numbers::pi : std::numbers::pi;
        skew = std::remainder(std::atan2(x.y, x.x) - *goal.heading_rad, period);
      }
      if (offset <= goal.tolerance_m && (goal.on_wheels || std::abs(p.z - t.z) < 0.2) &&
          std::abs(skew) <= goal.heading_tolerance_rad) {
        done_[g] = true;
        ++metrics_.moves_completed;
        metrics_.cycle_times_s.push_back(metrics_.time_s - last_completion_s_);
        last_completion_s_ = metrics_.time_s;
        metrics_.placement_offset_m.push_back(offset);
        if (goal.heading_rad)
          metrics_.placement_skew_deg.push_back(std::abs(skew) * 180.0 / std::numbers::pi);
      }
    }
  }
  if (metrics_.time_s > 0.0) metrics_.moves_per_hour = metrics_.moves_completed * 3600.0 / metrics_.time_s;
}

void Evaluator::observe_gantry_warning(bool horn, bool gantry_moving, double gantry_position_m) {
  if (horn) last_horn_s_ = metrics_.time_s;
  if (gantry_moving && !gantry_was_moving_) {
    travel_start_y_ = gantry_position_m;
    travel_warned_ = metrics_.time_s - last_horn_s_ <= exercise_.rules.horn_warning_s;
    travel_counted_ = false;
  }
  if (gantry_moving && !travel_warned_ && !travel_counted_ &&
      std::abs(gantry_position_m - travel_start_y_) > exercise_.rules.gantry_travel_m) {
    ++metrics_.unwarned_gantry_travel;
    travel_counted_ = true;
  }
  gantry_was_moving_ = gantry_moving;
}

Score score_of(const ExerciseSettings& exercise, const Metrics& metrics, bool goals_met,
               bool stopped_by_instructor) {
  const EvaluationRules& r = exercise.rules;
  Score s;
  auto deduct = [&](const char* reason, Skill skill, int count, double points) {
    if (count <= 0 || points <= 0.0) return;
    s.deductions.push_back({reason, count, count * points, skill});
    s.total -= count * points;
    s.skills[static_cast<std::size_t>(skill)] -= count * points;
  };
  deduct("collision", Skill::kSafety, metrics.collisions, r.points_collision);
  deduct("hard landing", Skill::kPrecision, metrics.hard_landings, r.points_hard_landing);
  deduct("landing while swaying", Skill::kPrecision, metrics.sway_landings, r.points_sway);
  deduct("twistlock misuse", Skill::kSafety, metrics.twistlock_misuse, r.points_twistlock_misuse);
  deduct("rope overload", Skill::kSafety, metrics.overloads, r.points_overload);
  deduct("limit switch hit", Skill::kPrecision, metrics.limit_hits, r.points_limit_hit);
  deduct("emergency stop", Skill::kSafety, metrics.emergency_stops, r.points_emergency_stop);
  deduct("gantry travel without the horn", Skill::kSafety, metrics.unwarned_gantry_travel,
         r.points_unwarned_travel);
  deduct("load dropped", Skill::kSafety, metrics.load_drops, r.points_load_drop);
  deduct("stop signal followed late", Skill::kSafety, metrics.late_stop_signals, r.points_late_stop_signal);
  deduct("lift with the hoist brake failed", Skill::kSafety, metrics.lifts_under_fault,
         r.points_lift_under_fault);
  // a machine taken out of service after a fault, as the procedure says, is excused the goals left
  const bool excused = metrics.stopped_after_fault;
  deduct("move not completed", Skill::kProductivity,
         excused ? 0 : static_cast<int>(exercise.moves.size()) - metrics.moves_completed,
         r.points_per_move_missing);
  deduct("discharge while swinging", Skill::kPrecision, metrics.swinging_releases, r.points_sway);
  deduct("tonne spilled", Skill::kPrecision, static_cast<int>(std::ceil(metrics.spilled_t - 1e-9)),
         r.points_per_spilled_t);
  deduct("poor bite", Skill::kProductivity, metrics.poor_bites, r.points_poor_bite);
  deduct("load-moment limiter trip", Skill::kSafety, metrics.limiter_trips, r.points_limiter_trip);
  deduct("outrigger pad lift-off", Skill::kSafety, metrics.pad_lift_offs, r.points_pad_lift_off);
  deduct("jack-knife", Skill::kSafety, metrics.jackknifes, r.points_jackknife);
  deduct("tip-over", Skill::kSafety, metrics.tip_overs, r.points_tip_over);
  deduct("speeding", Skill::kSafety, metrics.overspeeds, r.points_overspeed);
  int harsh = 0;
  for (const Metrics::Smoothness& axis : metrics.smoothness)
    harsh += axis.harsh_moves;
  deduct("harsh move", Skill::kPrecision, harsh, r.points_harsh_move);
  if (exercise.deliver && !excused)
    deduct("tonne short of the delivery", Skill::kProductivity,
           static_cast<int>(std::ceil(std::max(0.0, exercise.deliver->tonnes - metrics.delivered_t) - 1e-9)),
           r.points_per_missing_t);
  if (exercise.trim && !excused)
    deduct(
        "decimetre above the trim height", Skill::kProductivity,
        static_cast<int>(std::ceil(std::max(0.0, metrics.pile_top_m - exercise.trim->top_m) * 10.0 - 1e-9)),
        r.points_per_trim_dm);
  const int minutes_over = static_cast<int>(std::ceil(std::max(0.0, metrics.time_s - r.time_limit_s) / 60.0));
  deduct("minute over the time limit", Skill::kProductivity, minutes_over, r.points_per_minute_over);
  s.total = std::max(0.0, s.total);
  for (double& skill : s.skills)
    skill = std::max(0.0, skill);
  // a fault exercise's procedure followed stands for its goals; a fault the instructor injected does not
  const bool procedure_passes = excused && scripts_fault(exercise, MachineFault::kHoistBrake);
  if (s.total >= r.pass_score && (goals_met || procedure_passes))
    s.outcome = Outcome::kPassed;
  else if (!goals_met && !procedure_passes && (stopped_by_instructor || metrics.instructor_disruptions > 0))
    s.outcome = Outcome::kEndedByInstructor;
  else
    s.outcome = Outcome::kFailed;
  s.passed = s.outcome == Outcome::kPassed;
  return s;
}

Score Evaluator::score(bool stopped_by_instructor) const {
  return score_of(exercise_, metrics_, goals_met(), stopped_by_instructor);
}

}  // namespace harbour::sim

namespace harbour::sim {

std::vector<std::pair<std::string, double>> Metrics::rows() const {
  std::vector<std::pair<std::string, double>> r = {{"time_s", time_s},
                                                   {"moves_completed", moves_completed},
                                                   {"moves_per_hour", moves_per_hour},
                                                   {"collisions", collisions},
                                                   {"worst_collision_mps", worst_collision_mps},
                                                   {"collision_impulse_ns", collision_impulse_ns},
                                                   {"emergency_stops", emergency_stops}};
  // what a machine measures with its parts: its type's figures (without a type, every one of them, the
  // vehicle's where it is one)
  struct PartFigure {
    const char* name;
    double value;
    bool of_a_vehicle;
  };
  const auto figure = [](const char* name, double value, bool of_a_vehicle = false) {
    return PartFigure{name, value, of_a_vehicle};
  };
  const PartFigure parts[] = {figure("container_collisions", container_collisions),
                              figure("cell_guide_collisions", cell_guide_collisions),
                              figure("ship_collisions", ship_collisions),
                              figure("vehicle_collisions", vehicle_collisions),
                              figure("hard_landings", hard_landings),
                              figure("worst_landing_mps", worst_landing_mps),
                              figure("sway_landings", sway_landings),
                              figure("twistlock_misuse", twistlock_misuse),
                              figure("overloads", overloads),
                              figure("limit_hits", limit_hits),
                              figure("unwarned_gantry_travel", unwarned_gantry_travel),
                              figure("load_drops", load_drops),
                              figure("hoist_energy_j", hoist_energy_j),
                              figure("travel_energy_j", travel_energy_j),
                              figure("limiter_trips", limiter_trips),
                              figure("pad_lift_offs", pad_lift_offs),
                              figure("jackknifes", jackknifes, true),
                              figure("tip_overs", tip_overs, true),
                              figure("overspeeds", overspeeds, true),
                              figure("worst_overspeed_kmh", std::max(0.0, worst_overspeed_kmh), true)};
  for (const PartFigure& part : parts)
    if (machine ? machine->measures(part.name) : (!part.of_a_vehicle || vehicle))
      r.emplace_back(part.name, part.value);
  for (const Smoothness& axis : smoothness) {
    r.emplace_back(axis.axis + "_rms_jerk_mps3", axis.rms_jerk_mps3);
    r.emplace_back(axis.axis + "_harsh_moves", axis.harsh_moves);
  }
  if (signals > 0) {
    r.emplace_back("signals", signals);
    r.emplace_back("late_signals", late_signals);
    r.emplace_back("late_stop_signals", late_stop_signals);
    if (!signal_delays_s.empty()) {
      r.emplace_back("worst_signal_delay_s",
                     *std::max_element(signal_delays_s.begin(), signal_delays_s.end()));
      double sum = 0.0;
      for (const double d : signal_delays_s)
        sum += d;
      r.emplace_back("mean_signal_delay_s", sum / static_cast<double>(signal_delays_s.size()));
    }
  }
  if (team) {
    r.emplace_back("team_near_misses", team->near_misses);
    r.emplace_back("team_contacts", team->contacts);
    if (team->closest_m >= 0.0) r.emplace_back("team_closest_m", team->closest_m);
    if (team->hand_offs > 0) {
      r.emplace_back("team_hand_offs", team->hand_offs);
      r.emplace_back("team_worst_hand_off_ms", team->worst_hand_off_ms);
    }
    if (team->waited_s >= 0.0) r.emplace_back("team_waited_s", team->waited_s);
  }
  if (!placement_offset_m.empty())
    r.emplace_back("worst_placement_offset_m",
                   *std::max_element(placement_offset_m.begin(), placement_offset_m.end()));
  if (!placement_skew_deg.empty())
    r.emplace_back("worst_placement_skew_deg",
                   *std::max_element(placement_skew_deg.begin(), placement_skew_deg.end()));
  if (hoist_fault) {
    r.emplace_back("lifts_under_fault", lifts_under_fault);
    r.emplace_back("stopped_after_fault", stopped_after_fault ? 1.0 : 0.0);
    if (fault_set_down_s >= 0.0) r.emplace_back("fault_set_down_s", fault_set_down_s);
  }
  if (instructor_disruptions > 0) r.emplace_back("instructor_disruptions", instructor_disruptions);
  if (!bulk) return r;
  double fill_sum = 0.0, swing_max = 0.0;
  for (double f : bite_fill)
    fill_sum += f;
  for (double s : release_swing_m)
    swing_max = std::max(swing_max, s);
  const std::pair<std::string, double> more[] = {
      {"delivered_t", delivered_t},
      {"handled_t", handled_t},
      {"spilled_t", spilled_t},
      {"spilled_percent", spilled_percent},
      {"tonnes_per_hour", tonnes_per_hour},
      {"bites", static_cast<double>(bite_fill.size())},
      {"mean_bite_fill", bite_fill.empty() ? 0.0 : fill_sum / static_cast<double>(bite_fill.size())},
      {"poor_bites", poor_bites},
      {"worst_release_swing_m", swing_max},
      {"swinging_releases", swinging_releases}};
  r.insert(r.end(), std::begin(more), std::end(more));
  if (trim) r.emplace_back("pile_top_m", pile_top_m);
  return r;
}

namespace {
// every counted event: its name, its count and the figure stored with it
struct CountedKind {
  const char* name;
  int Metrics::*count;
  double Metrics::*value;  // nullptr: none
};
constexpr std::array<CountedKind, kCountedEventKinds> kCountedKinds{{
    {"collision", &Metrics::collisions, &Metrics::worst_collision_mps},
    {"hard_landing", &Metrics::hard_landings, &Metrics::worst_landing_mps},
    {"sway_landing", &Metrics::sway_landings, nullptr},
    {"twistlock_misuse", &Metrics::twistlock_misuse, nullptr},
    {"rope_overload", &Metrics::overloads, nullptr},
    {"limit_switch_hit", &Metrics::limit_hits, nullptr},
    {"emergency_stop", &Metrics::emergency_stops, nullptr},
    {"gantry_travel_without_horn", &Metrics::unwarned_gantry_travel, nullptr},
    {"limiter_trip", &Metrics::limiter_trips, nullptr},
    {"pad_lift_off", &Metrics::pad_lift_offs, nullptr},
    {"poor_bite", &Metrics::poor_bites, nullptr},
    {"swinging_release", &Metrics::swinging_releases, nullptr},
    {"jackknife", &Metrics::jackknifes, nullptr},
    {"tip_over", &Metrics::tip_overs, nullptr},
    {"speeding", &Metrics::overspeeds, &Metrics::worst_overspeed_kmh},
    {"load_drop", &Metrics::load_drops, nullptr},
    {"lift_under_fault", &Metrics::lifts_under_fault, nullptr},
    {"late_stop_signal", &Metrics::late_stop_signals, nullptr},
}};
}  // namespace

const char* counted_event_kind(std::size_t n) {
  return kCountedKinds[n].name;
}

Progress progress(const Metrics& metrics) {
  Progress p;
  p.time_s = metrics.time_s;
  p.moves_completed = metrics.moves_completed;
  const std::size_t done = metrics.cycle_times_s.size();
  for (std::size_t k = 0; k < Progress::kRecentMoves && k < done; ++k)
    p.recent_cycle_times_s[Progress::kRecentMoves - 1 - k] = metrics.cycle_times_s[done - 1 - k];
  for (std::size_t n = 0; n < kCountedEventKinds; ++n) {
    p.counts[n] = metrics.*kCountedKinds[n].count;
    p.values[n] = kCountedKinds[n].value ? metrics.*kCountedKinds[n].value : 0.0;
  }
  return p;
}

std::vector<CountedEvent> counted_events(const Progress& before, const Progress& now) {
  std::vector<CountedEvent> events;
  for (std::size_t n = 0; n < kCountedEventKinds; ++n)
    for (int k = before.counts[n]; k < now.counts[n]; ++k)
      events.push_back({kCountedKinds[n].name, now.values[n]});
  return events;
}

std::vector<CountedEvent> counted_events(const Metrics& before, const Metrics& now) {
  return counted_events(progress(before), progress(now));
}

}  // namespace harbour::sim
