#include "harbour/machines/GantryAutopilot.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "harbour/core/Units.h"
#include "harbour/machines/mhc/BoomSteering.h"
#include "harbour/machines/rtg/RubberTyredGantry.h"
#include "harbour/sim/Vessel.h"

namespace harbour::sim {
namespace {

constexpr double kTravelHeight_m = 22.0;    // spreader centre while travelling: clears the vessel's stack
constexpr double kBelowUpperLimit_m = 0.3;  // ... or, on a lower crane, this far under its upper limit
constexpr double kStackClearance_m = 1.0;   // in a yard: the load's underside this far over the stacks
constexpr double kCruiseLever = 0.75;       // travel at three quarters of full speed
constexpr double kSlowZone_m = 1.5;         // lower slowly over the last metre and a half
constexpr double kEaseRaise_s = 1.0;        // the raise slows over its last second
constexpr double kEasedRaiseLever = 0.2;
constexpr double kSlowLever = 0.08;           // 0.12 m/s at the spreader on the STS hoist
constexpr double kTunedHoistSpeed_mps = 1.5;  // the hoist levers are set for a spreader this fast at full
                                              // lever (the STS's); a slower hoist gets them scaled up
constexpr double kPosition_tolerance_m = 0.03;
constexpr double kSettled_m = 0.05;    // swing and position error small enough to start lowering
constexpr double kHover_m = 0.5;       // hold this far above the landing until on target and calm
constexpr double kPickUpAim_m = 0.02;  // the twistlocks' cones reach 30 mm
constexpr double kLookAhead_s = 0.5;
// an operator's hand on a device: new lever positions 50 times a second, at a joystick axis' resolution
constexpr std::int64_t kDecisionSteps = 20;
constexpr double kDecision_s = kDecisionSteps * Simulation::kStep_s;
constexpr double kLeverCounts = 32767.0;

constexpr double kCaughtUp = 1e-3;  // a taken-over lever this near the operator's own has caught up

double device_lever(double lever) {
  return std::round(std::clamp(lever, -1.0, 1.0) * kLeverCounts) / kLeverCounts;
}
constexpr double kCellEntryClearance_m = 0.3;  // aim the spreader this far above the coaming top
constexpr double kCellEntryBand_m = 0.3;       // ... holding within this band below that height
constexpr double kFineSpeed_mps = 0.2;         // fine positioning never drives faster
constexpr double kResting_s = 1.0;             // the spreader sits beside the castings this long: lift off
// lowering without coming kProgress_m lower for kStalled_s (waiting for an aim it never reaches, leaning on a
// neighbouring stack): lift off and come down again
constexpr double kStalled_s = 30.0;
constexpr double kProgress_m = 0.01;
constexpr double kLiftOffLever = 0.15;  // ... at 0.22 m/s
constexpr double kLiftOff_s = 2.0;
constexpr double kButton_s = 0.1;
constexpr double kSeated_s = 0.2;     // the landed lamp lit this long before the locks are turned
constexpr double kLockRetry_s = 1.0;  // not locked this long after the button: land again
constexpr double kSlacken_s = 0.6;
constexpr double kHorn_s = 1.0;  // the horn sounds this long before the gantry travels
// holding a steered gantry's line: the offset closes over kLaneClose_s (its integral over kLaneIntegral_s
// takes out a steering bias), the heading reaches its aim over kHeadingClose_s
constexpr double kLaneClose_s = 5.0;
constexpr double kLaneIntegral_s = 8.0;
constexpr double kHeadingClose_s = 1.5;
constexpr double kMaxHeadingAim_rad = 0.03;
constexpr double kSteerFromSpeed_mps = 0.1;

}  // namespace

std::string GantryAutopilot::why_cannot_drive(const ExerciseSettings& exercise) {
  const char* machine = exercise.scenario.machine.kind();
  const auto* rtg = exercise.scenario.machine.get_if<RtgSetup>();
  if (std::string(machine) != "sts" && !rtg)
    return std::string("the autopilot drives the STS's and the RTG's container moves; not the ") + machine +
           "'s";
  if (rtg && std::abs(std::remainder(rtg->start.heading_rad, 2.0 * std::numbers::pi)) > 1e-9)
    return "the autopilot drives an RTG standing square to the world (heading 0)";
  if (exercise.moves.empty()) return "the exercise has no moves for the autopilot to make";
  return {};
}

GantryAutopilot::GantryAutopilot(const ExerciseSettings& exercise, OperatorDefects defects)
    : exercise_(exercise), defects_(defects) {
  if (const std::string why = why_cannot_drive(exercise); !why.empty()) throw std::invalid_argument(why);
}

const GantryCrane& GantryAutopilot::crane(const Simulation& simulation) {
  if (const auto* crane = dynamic_cast<const GantryCrane*>(&simulation.machine())) return *crane;
  throw std::logic_error("the autopilot drives a gantry crane");  // why_cannot_drive() refused the others
}

std::size_t GantryAutopilot::goal_index(const Simulation& simulation) const {
  const auto& items = simulation.scenario().containers;
  for (std::size_t n = 0; n < items.size(); ++n)
    if (items[n].id == exercise_.moves[goal_].container_id) return n;
  throw std::logic_error("exercise move names no scenario item");  // the loader checks it
}

double GantryAutopilot::goal_half_height(const Simulation& simulation) const {
  return simulation.scenario().containers[goal_index(simulation)].half_extents_m.z;
}

std::optional<double> GantryAutopilot::cell_entry_z(const Simulation& simulation) const {
  const ContainerPlacement& item = simulation.scenario().containers[goal_index(simulation)];
  if (!item.in_cell || carrying_ || !simulation.vessel()) return std::nullopt;
  const Vessel& vessel = *simulation.vessel();
  const double coaming = vessel.frame().to_parent({0, 0, vessel.geometry().coaming_top_m()}).z;
  return coaming + kCellEntryClearance_m + crane(simulation).spreader_hoist().spreader().half_extents_m().z;
}

core::Vec3 GantryAutopilot::source(const Simulation& simulation) const {
  return simulation.world().pose(simulation.container_body(goal_index(simulation))).position;
}

std::array<bool, 4> GantryAutopilot::flippers(const Simulation& simulation) const {
  // down for a box standing free (the flippers would land on a neighbour at the deck's row pitch), up in
  // the cell guides and for hatch covers (wider than the frame)
  const std::size_t goal = goal_index(simulation);
  const ContainerPlacement& item = simulation.scenario().containers[goal];
  if (item.kind != ContainerPlacement::Kind::kContainer || item.in_cell) return {};
  const core::Pose at = simulation.world().pose(simulation.container_body(goal));
  for (const ContainerRef& other : simulation.liftables()) {
    if (other.body == simulation.container_body(goal)) continue;
    const core::Vec3 d = at.to_local(simulation.world().pose(other.body).position);
    const bool beside = std::abs(d.z) < item.half_extents_m.z + other.half_extents_m.z - 0.1 &&
                        std::abs(d.x) < item.half_extents_m.x + other.half_extents_m.x &&
                        std::abs(d.y) < item.half_extents_m.y + other.half_extents_m.y + 0.5;
    if (beside) return {};
  }
  return {true, true, true, true};
}

double GantryAutopilot::height_over_stacks(const Simulation& simulation,
                                           const core::Vec3& destination) const {
  // the spreader's centre height at which the load's underside clears every box under its way from here to
  // the destination (the footprints' bounding boxes at both ends and between) by kStackClearance_m
  const SpreaderHoist& hoist = crane(simulation).spreader_hoist();
  const physics::BodyId load = carrying_ ? *hoist.locked_container() : hoist.spreader_body();
  const core::Pose at = simulation.world().pose(load);
  const core::Vec3 half = carrying_ ? simulation.scenario().containers[goal_index(simulation)].half_extents_m
                                    : hoist.spreader().half_extents_m();
  // half the bounding box of a box's footprint along world x and y
  const auto reach = [](const core::Pose& pose, const core::Vec3& h) {
    const core::Vec3 a = pose.rotation.column(0), b = pose.rotation.column(1);
    return std::pair{std::abs(a.x) * h.x + std::abs(b.x) * h.y, std::abs(a.y) * h.x + std::abs(b.y) * h.y};
  };
  const auto [load_x, load_y] = reach(at, half);
  const double min_x = std::min(at.position.x, destination.x) - load_x;
  const double max_x = std::max(at.position.x, destination.x) + load_x;
  const double min_y = std::min(at.position.y, destination.y) - load_y;
  const double max_y = std::max(at.position.y, destination.y) + load_y;
  double top = destination.z;
  for (const ContainerRef& box : simulation.liftables()) {
    if (box.body == load) continue;
    const core::Pose pose = simulation.world().pose(box.body);
    const auto [bx, by] = reach(pose, box.half_extents_m);
    if (pose.position.x + bx > min_x && pose.position.x - bx < max_x && pose.position.y + by > min_y &&
        pose.position.y - by < max_y)
      top = std::max(top, pose.position.z + box.half_extents_m.z);
  }
  const double hanging = carrying_ ? 2.0 * half.z : 0.0;  // the box below the spreader
  return top + kStackClearance_m + hanging + hoist.spreader().half_extents_m().z;
}

void GantryAutopilot::start_travel(const core::Vec3& to, double gantry_y, double now) {
  trolley_ = {to.x, 0.0, now, false, 0.0, -1.0};
  // a gantry travel waits for the horn
  const bool gantry_travels = std::abs(to.y - gantry_y) > kPosition_tolerance_m && !defects_.skip_horn;
  gantry_ = {to.y, 0.0, gantry_travels ? now + kHorn_s : now, false, 0.0, -1.0};
}

double GantryAutopilot::axis_lever(AxisMove& m, double position, double max_speed, double period,
                                   double now) const {
  // trapezoid in the lever: ramp up over exactly one period (so the swing it starts ends with the ramp),
  // brake over one period when the remaining distance equals what a linear ramp-down covers (v T / 2), then
  // creep onto the target. A move too short to reach cruise ramps to a lower top, still over one period.
  if (now < m.ramp_start) return 0.0;  // not started yet
  const double error = m.target - position;
  if (!m.decelerating && std::abs(error) < kPosition_tolerance_m) return 0.0;  // fine positioning's job
  const double direction = error >= 0.0 ? 1.0 : -1.0;
  if (m.top < 0.0) m.top = std::min(kCruiseLever, std::abs(error) / (max_speed * period));
  if (!m.decelerating) {
    m.peak = std::min(m.top, m.top * (now - m.ramp_start) / period);
    if (std::abs(error) <= m.peak * max_speed * period / 2.0 && m.peak > 0.0) {
      m.decelerating = true;
      m.decel_from = m.peak;
      m.ramp_start = now;
    } else {
      return direction * m.peak;
    }
  }
  const double braking = m.decel_from * (1.0 - (now - m.ramp_start) / period);
  if (braking > 0.0) return direction * braking;
  return 0.0;  // braked: fine positioning takes over
}

double GantryAutopilot::catch_swing(SwingAxis& axis, double target, double axis_position, double axis_speed,
                                    double load_position, double load_speed, double wind_lean, double period,
                                    double max_speed) {
  // load offset s from the axis; pendulum: s'' = -w^2 (s - s0) - a_axis. An axis speed k (s - s0) gives
  // s'' + k s' + w^2 (s - s0) = 0: damping ratio k / 2w. s0, where the load hangs at rest, is the wind's
  // lean (it changes with the rope length and the gusts) plus the rope geometry's offset, s less the lean
  // filtered over a period.
  const double offset = load_position - axis_position - wind_lean;
  if (!axis.primed) {
    axis.rest_offset = offset;
    axis.last_target = target;
    axis.primed = true;
  }
  // the target moves with the vessel; where the load will be relative to it shortly
  const double closing = load_speed - (target - axis.last_target) / kDecision_s;
  axis.last_target = target;
  axis.miss =
      std::max(std::abs(target - load_position), std::abs(target - load_position - closing * kLookAhead_s));
  axis.rest_offset += (offset - axis.rest_offset) * kDecision_s / period;
  const double omega = 2.0 * std::numbers::pi / period;
  const double swing = offset - axis.rest_offset;
  axis.swing = std::hypot(swing, (load_speed - axis_speed) / omega);
  axis.error = target - (axis_position + axis.rest_offset + wind_lean);
  const double speed = 0.25 * omega * axis.error + omega * swing;
  return std::clamp(speed, -kFineSpeed_mps, kFineSpeed_mps) / max_speed;
}

void GantryAutopilot::position_finely(const Simulation& simulation, const core::Vec3& destination,
                                      double period, GantryLevers& in) {
  const GantryCrane& c = crane(simulation);
  const SpreaderHoist& hoist = c.spreader_hoist();
  const physics::BodyId load = carrying_ ? *hoist.locked_container() : hoist.spreader_body();
  const core::Vec3 at = simulation.world().pose(load).position;
  const core::Vec3 v = simulation.world().linear_velocity(load);
  // where the load would hang in the wind blowing now: the operator leans into the gusts
  const core::Vec3 lean =
      simulation.wind_rest_offset_m(simulation.weather().wind(), hoist.locked_container());
  in.trolley = catch_swing(trolley_swing_, destination.x, c.trolley_x_m(), c.trolley_reference_mps(), at.x,
                           v.x, lean.x, period, c.trolley_max_speed_mps());
  in.gantry = catch_swing(gantry_swing_, destination.y, c.gantry_y_m(), c.gantry_reference_mps(), at.y, v.y,
                          lean.y, period, c.gantry_max_speed_mps());
}

bool GantryAutopilot::will_land_within(double tolerance) const {
  return trolley_swing_.miss < tolerance && gantry_swing_.miss < tolerance;
}

bool GantryAutopilot::on_target(double tolerance) const {
  return trolley_swing_.swing < tolerance && gantry_swing_.swing < tolerance &&
         std::abs(trolley_swing_.error) < tolerance && std::abs(gantry_swing_.error) < tolerance;
}

const char* GantryAutopilot::activity() const {
  switch (phase_) {
    case Phase::kRaise:
      return "raise";
    case Phase::kTravel:
      return "travel";
    case Phase::kSettle:
      return "settle";
    case Phase::kLower:
      return "lower";
    case Phase::kLiftOff:
      return "lift off";
    case Phase::kLock:
      return "lock";
    case Phase::kSlacken:
      return "slacken";
    case Phase::kUnlock:
      return "unlock";
  }
  return "";
}

void GantryAutopilot::resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) {
  hand_ = hand_before_ = levers;
  catching_up_ = true;
  goal_ = static_cast<std::size_t>(std::max(0, moves_done));
  phase_ = Phase::kRaise;
  phase_start_ = simulation.time_s();
  stalled_since_ = landed_since_ = -1.0;
  decided_ = false;
  trolley_swing_ = {};
  gantry_swing_ = {};
  carrying_ = !done() && crane(simulation).spreader_hoist().locked_container() ==
                             std::optional(simulation.container_body(goal_index(simulation)));
}

scene::Controls GantryAutopilot::next(const Simulation& simulation) {
  if (simulation.steps() % kDecisionSteps != 0 && decided_) return last_controls_;
  last_ = decide(simulation);
  last_.steer = steer(simulation);
  for (double* lever : {&last_.gantry, &last_.trolley, &last_.hoist, &last_.steer})
    *lever = device_lever(*lever);
  last_controls_ = crane(simulation).crane_controls(last_);
  if (catching_up_) last_controls_ = catch_up(simulation.control_table(), last_controls_);
  decided_ = true;
  return last_controls_;
}

scene::Controls GantryAutopilot::catch_up(const scene::ControlTable& table, const scene::Controls& wanted) {
  // after a take-over the levers move from where they stood to where this operator wants them as a hand moves
  // them; once every one is there (to the hand's resolution) they follow the decisions directly
  scene::Controls out = wanted;
  bool caught_up = true;
  for (int slot = 0; slot < table.size(); ++slot) {
    if (table[slot].kind != scene::ControlKind::kAxis) continue;
    const auto at = static_cast<std::size_t>(slot);
    out.value[at] =
        device_lever(hand_lever(hand_.value[at], hand_before_.value[at], wanted.value[at], kDecision_s));
    caught_up = caught_up && std::abs(out.value[at] - wanted.value[at]) <= kCaughtUp;
  }
  hand_before_ = std::exchange(hand_, out);
  catching_up_ = !caught_up;
  return out;
}

double GantryAutopilot::steer(const Simulation& simulation) {
  // as a driver holds a line: aim the heading back at it (the offset e closes as de/dt = -v ψ, so the aim
  // ψ = e / (v τ) closes it over τ) and turn at the rate that reaches that aim
  const GantryCrane& c = crane(simulation);
  const double v = c.gantry_reference_mps();
  if (std::abs(v) < kSteerFromSpeed_mps || defects_.never_steer) return 0.0;
  const double offset = c.lane_offset_m();
  lane_integral_ += offset * kDecision_s;
  const double aim = std::clamp((offset + lane_integral_ / kLaneIntegral_s) / (v * kLaneClose_s),
                                -kMaxHeadingAim_rad, kMaxHeadingAim_rad);
  return c.steer_lever((aim - c.yaw_rad()) / kHeadingClose_s);
}

GantryLevers GantryAutopilot::decide(const Simulation& simulation) {
  GantryLevers in;
  const GantryCrane& crane = GantryAutopilot::crane(simulation);
  const SpreaderHoist& hoist = crane.spreader_hoist();
  const core::Vec3 spreader = simulation.world().pose(hoist.spreader_body()).position;
  const double highest_travel = std::min(kTravelHeight_m, hoist.upper_limit_m() - kBelowUpperLimit_m);
  const double spreader_weight_n = hoist.spreader_mass_kg() * core::kStandardGravity;
  if (simulation.machine().fault_active(MachineFault::kHoistBrake) &&
      (!carrying_ || defects_.stop_at_fault)) {
    // the brake fault lamp: with the load down (the move in hand finished under power), set the empty
    // spreader down and stop the crane; a panicking operator stops at once and the load falls
    const bool resting = hoist.hoisted_load_n() < 0.5 * spreader_weight_n;
    in.emergency_stop = defects_.stop_at_fault || resting;
    in.hoist = in.emergency_stop ? 0.0 : -kSlowLever;
    return in;
  }
  if (done()) {  // clear the truck: raise the empty spreader to travel height
    in.hoist = spreader.z < highest_travel ? 1.0 : 0.0;
    return in;
  }
  const double now = simulation.time_s();
  // a team's truck not yet under the crane: over its stop, waiting for it
  const std::optional<core::Vec3> target =
      carrying_ ? move_target(exercise_.moves[goal_], simulation) : std::nullopt;
  const core::Vec3 destination = !carrying_ ? source(simulation)
                                 : target   ? *target
                                            : exercise_.moves[goal_].target_m;
  const double travel_height = simulation.vessel()
                                   ? highest_travel
                                   : std::min(highest_travel, height_over_stacks(simulation, destination));
  const double hoist_scale = std::max(1.0, kTunedHoistSpeed_mps / hoist.full_hoist_speed_mps());
  const auto hoist_lever = [&](double lever) { return std::clamp(lever * hoist_scale, -1.0, 1.0); };
  const double period =
      2.0 * std::numbers::pi * std::sqrt(std::max(hoist.pendulum_length_m(), 1.0) / core::kStandardGravity);
  in.flipper_down = flippers(simulation);
  auto enter = [&](Phase p) {
    phase_ = p;
    phase_start_ = now;
    stalled_since_ = landed_since_ = -1.0;
  };

  switch (phase_) {
    case Phase::kRaise:
      // easing the lever over the last second's rise (a hoist stopped from full speed jerks the load)
      in.hoist = std::clamp((travel_height - spreader.z) / (hoist.full_hoist_speed_mps() * kEaseRaise_s),
                            kEasedRaiseLever, 1.0);
      if (spreader.z >= travel_height) {
        start_travel(destination, crane.gantry_y_m(), now);
        enter(Phase::kTravel);
      }
      break;
    case Phase::kTravel: {
      in.trolley = axis_lever(trolley_, crane.trolley_x_m(), crane.trolley_max_speed_mps(), period, now);
      in.gantry = axis_lever(gantry_, crane.gantry_y_m(), crane.gantry_max_speed_mps(), period, now);
      in.horn = now < gantry_.ramp_start;
      // (at an axis' ramp start its lever is still 0)
      const bool started = now > std::max(trolley_.ramp_start, gantry_.ramp_start);
      if (in.trolley == 0.0 && in.gantry == 0.0 && !in.horn && started) {
        trolley_swing_ = {};
        gantry_swing_ = {};
        enter(Phase::kSettle);
      }
      break;
    }
    case Phase::kSettle:
      // catch the swing and creep onto the target before lowering (four periods at most)
      position_finely(simulation, destination, period, in);
      if (carrying_ && !target) {
        phase_start_ = now;  // settling over the stop until the truck is there
      } else if ((on_target(kSettled_m) && now - phase_start_ > 0.5) || now - phase_start_ > 4 * period) {
        enter(Phase::kLower);
      }
      break;
    case Phase::kLower: {
      position_finely(simulation, destination, period, in);
      // landing surface: the spreader's centre when seated on the box (pick-up) or with the box on its target
      const double land_z =
          destination.z + goal_half_height(simulation) + hoist.spreader().half_extents_m().z;
      const double above = spreader.z - land_z;
      const double aim = carrying_ ? exercise_.moves[goal_].tolerance_m / 4.0 : kPickUpAim_m;
      // into a hold cell: slow down and aim above the cell guides too (25 mm clearance a side)
      const std::optional<double> entry = cell_entry_z(simulation);
      const bool at_entry = entry && spreader.z < *entry && spreader.z > *entry - kCellEntryBand_m;
      const bool slow = (above < kSlowZone_m ||
                         (entry && spreader.z - *entry < kSlowZone_m && !at_entry && spreader.z > *entry)) &&
                        !(carrying_ && defects_.land_fast);
      const bool hold =
          (above < kHover_m || at_entry) && !will_land_within(aim) && !(carrying_ && defects_.land_fast);
      in.hoist = hold ? 0.0 : hoist_lever(slow ? -kSlowLever : -0.6);
      if (stalled_since_ < 0.0 || spreader.z < stalled_z_ - kProgress_m) {
        stalled_since_ = now;
        stalled_z_ = spreader.z;
      }
      if (now - stalled_since_ > kStalled_s) enter(Phase::kLiftOff);
      // the landed lamp lit steadily (not a touch it bounces off) before the locks are turned
      const bool landed = hoist.locks().twistlocks().lamps().landed;
      if (!landed || landed_since_ < 0.0) landed_since_ = landed ? now : -1.0;
      if (!carrying_ && landed && now - landed_since_ >= kSeated_s) enter(Phase::kLock);
      if (carrying_ && simulation.world().pose(*hoist.locked_container()).position.z <= destination.z + 0.01)
        enter(Phase::kSlacken);
      // sitting on the box beside its castings: lift off and aim again
      const bool resting = hoist.hoisted_load_n() < 0.5 * spreader_weight_n;
      if (!carrying_ && !hoist.locks().twistlocks().lamps().landed && resting) {
        if (resting_since_ < 0.0) resting_since_ = now;
        if (now - resting_since_ > kResting_s) enter(Phase::kLiftOff);
      } else {
        resting_since_ = -1.0;
      }
      break;
    }
    case Phase::kLiftOff:
      position_finely(simulation, destination, period, in);
      in.hoist = hoist_lever(kLiftOffLever);
      if (now - phase_start_ > kLiftOff_s) {
        resting_since_ = -1.0;
        enter(Phase::kLower);
      }
      break;
    case Phase::kLock:
      if (defects_.forget_lock_once && !lock_skipped_) {
        lock_skipped_ = true;  // hoists straight away without locking, then has to come back down
        enter(Phase::kRaise);
        break;
      }
      in.lock = now - phase_start_ < kButton_s;
      if (now - phase_start_ > 2 * kButton_s && hoist.locked_container()) {
        carrying_ = true;
        enter(Phase::kRaise);
      } else if (now - phase_start_ > kLockRetry_s) {
        enter(Phase::kLower);  // the locks did not turn: settle onto the castings again
      }
      break;
    case Phase::kSlacken:
      // lower on until the ropes carry the spreader alone (the unlock interlock refuses a hanging load)
      in.hoist = hoist_lever(-kSlowLever);
      if (now - phase_start_ > kSlacken_s && hoist.hoisted_load_n() < 1.15 * spreader_weight_n)
        enter(Phase::kUnlock);
      break;
    case Phase::kUnlock:
      in.unlock = now - phase_start_ < kButton_s;
      if (now - phase_start_ > 2 * kButton_s && !hoist.locked_container()) {
        carrying_ = false;
        ++goal_;
        enter(Phase::kRaise);
      }
      break;
  }
  return in;
}

}  // namespace harbour::sim
