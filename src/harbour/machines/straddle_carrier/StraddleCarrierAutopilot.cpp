#include "harbour/machines/straddle_carrier/StraddleCarrierAutopilot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harbour/machines/parts/PurePursuit.h"
#include "harbour/machines/straddle_carrier/StraddleCarrier.h"

namespace harbour::sim {
namespace {

constexpr double kCruise_mps = 3.0;  // along a row, laden or not
constexpr double kCorner_mps = 1.2;  // with the wheel turned kCornerSteer or more
constexpr double kCornerSteer = 0.3;
constexpr double kCreep_mps = 0.25;       // the last metre to a stop
constexpr double kInch_mps = 0.04;        // the slowest it moves to correct a stop
constexpr double kStopping_mps2 = 0.4;    // the deceleration it plans its stops with
constexpr double kStopped_m = 0.02;       // a stop this near is where it means to be
constexpr double kSpeedGain = 0.6;        // pedal per m/s of speed error
constexpr double kPedalRate_per_s = 0.6;  // how fast a foot moves a pedal
constexpr double kLookahead_m = 8.0;
constexpr double kOnTheRow_m = 1.0;       // stacks this near its way stand under it
constexpr double kClearance_m = 0.5;      // the spreader's (or the box's) underside over the stacks it passes
constexpr double kHover_m = 0.3;          // above where it lands, before it comes down slowly
constexpr double kLandingLever = 0.25;    // the hoist lever for the last 0.3 m down
constexpr double kHoistGain_per_m = 2.0;  // the hoist lever per metre from its height
constexpr double kSteady_m = 0.02;  // the spreader's swing and the portal's error it catches before it lands
constexpr double kTwentyFootHalfLength_m = 4.0;

core::Vec3 flat(core::Vec3 v) {
  v.z = 0.0;
  return v;
}

// the highest stack top under a way (the box carried apart)
double highest_stack_top(const Simulation& simulation, const std::vector<core::Vec3>& way,
                         const ContainerRef& box) {
  double highest = 0.0;
  for (const ContainerRef& other : simulation.liftables()) {
    if (other.body == box.body) continue;
    const core::Vec3 p = simulation.world().pose(other.body).position;
    if (core::length(flat(p) - point_ahead(way, p, 0.0)) < kOnTheRow_m)
      highest = std::max(highest, p.z + other.half_extents_m.z);
  }
  return highest;
}

}  // namespace

std::string StraddleCarrierAutopilot::why_cannot_drive(const ExerciseSettings& exercise) {
  const auto* setup = exercise.scenario.machine.get_if<StraddleCarrierSetup>();
  if (!setup) return "the straddle carrier autopilot drives a straddle carrier";
  if (exercise.moves.size() != 1) return "the straddle carrier autopilot makes one move (exercise.moves)";
  const core::Vec3 along{std::cos(setup->start.heading_rad), std::sin(setup->start.heading_rad), 0.0};
  const core::Vec3 left{-along.y, along.x, 0.0};
  const MoveGoal& goal = exercise.moves[0];
  const ContainerPlacement* box = nullptr;
  for (const ContainerPlacement& c : exercise.scenario.containers)
    if (c.id == goal.container_id) box = &c;
  if (!box) return "the move's box is not in the exercise";
  const core::Vec3 to_box = flat(box->pose.position - setup->start.position_m);
  if (std::abs(dot(to_box, left)) > 0.05 || dot(to_box, along) <= 0.0)
    return "the straddle carrier autopilot picks the box ahead on its line";
  const core::Vec3 to_target = flat(goal.target_m - setup->start.position_m);
  if (exercise.route_m.empty() &&
      (std::abs(dot(to_target, left)) > 0.05 || dot(to_target, along) <= dot(to_box, along)))
    return "the straddle carrier autopilot drives along one row without a route (exercise.route_m): the "
           "target "
           "further along the box's line";
  return "";
}

StraddleCarrierAutopilot::StraddleCarrierAutopilot(const ExerciseSettings& exercise) : exercise_(exercise) {
  if (const std::string why = why_cannot_drive(exercise_); !why.empty()) throw std::invalid_argument(why);
  // its way: from behind where it starts (room to back up), along the row, the route, to the target and on
  const auto& setup = exercise.scenario.machine.as<StraddleCarrierSetup>();
  const core::Vec3 start = flat(setup.start.position_m);
  const core::Vec3 along{std::cos(setup.start.heading_rad), std::sin(setup.start.heading_rad), 0.0};
  path_ = {start - along * 50.0, start};
  for (const core::Vec3& point : exercise.route_m)
    path_.push_back(flat(point));
  const core::Vec3 target = flat(exercise.moves[0].target_m);
  const core::Vec3 last_leg = target - path_.back();
  path_.push_back(target);
  path_.push_back(target + last_leg * (50.0 / core::length(last_leg)));
  while (exercise.scenario.containers[box_index_].id != exercise.moves[0].container_id)
    ++box_index_;
}

const char* StraddleCarrierAutopilot::activity() const {
  constexpr const char* kNames[] = {"approach", "land",   "lock",  "lift", "carry",
                                    "set",      "unlock", "clear", "done"};
  return kNames[static_cast<int>(phase_)];
}

void StraddleCarrierAutopilot::resume(const Simulation& simulation, int moves_done,
                                      const scene::Controls& levers) {
  const auto* machine = dynamic_cast<const StraddleCarrier*>(&simulation.machine());
  phase_ = moves_done >= 1 ? Phase::kDone : machine && machine->held_item() ? Phase::kLift : Phase::kApproach;
  phase_start_s_ = simulation.time_s();
  take_levers(levers);
}

scene::Controls StraddleCarrierAutopilot::decide(const Simulation& simulation, const StraddleCarrier& m) {
  const scene::ControlTable& table = simulation.control_table();
  scene::Controls c = table.neutral();
  const auto set = [&](const char* label, double value) {
    c.value[static_cast<std::size_t>(table.find(label))] = value;
  };
  const auto press = [&](const char* label, double value) {  // a pedal moves as a foot moves it
    const auto slot = static_cast<std::size_t>(table.find(label));
    const double was = last_decision().value[slot];
    const double most = kPedalRate_per_s * static_cast<double>(kDecisionSteps) * Simulation::kStep_s;
    c.value[slot] = was + std::clamp(value - was, -most, most);
  };
  const double now = simulation.time_s();
  const auto enter = [&](Phase next) {
    phase_ = next;
    phase_start_s_ = now;
  };
  const physics::PhysicsWorld& world = simulation.world();
  const SpreaderHoist& rig = m.spreader_hoist();
  const MoveGoal& goal = exercise_.moves[0];
  const ContainerRef& box_ref = simulation.liftables()[box_index_];
  const double box_height = 2.0 * box_ref.half_extents_m.z;
  const double spreader_half_height = rig.spreader().half_extents_m().z;
  const core::Pose portal = world.pose(m.body());
  const double at_along = distance_along(path_, portal.position);
  const core::Pose box_pose = world.pose(box_ref.body);
  const ContainerPlacement& placed = exercise_.scenario.containers[box_index_];  // where the box stood
  const double box_along = distance_along(path_, placed.pose.position);
  const double target_along = distance_along(path_, goal.target_m);
  // its way's direction where it stands
  const core::Vec3 way =
      flat(point_ahead(path_, portal.position, 1.0) - point_ahead(path_, portal.position, 0.0));
  const core::Vec3 heading = way * (1.0 / std::max(1e-9, core::length(way)));

  const double highest_top = std::max(highest_stack_top(simulation, path_, box_ref),
                                      placed.pose.position.z + placed.half_extents_m.z);
  const double carry_z = highest_top + kClearance_m + box_height + spreader_half_height;
  const double spreader_z = m.spreader_pose().position.z;

  // the hoist towards a height, slowly for its last `slow_m`
  const auto hoist_to = [&](double z, double slow_m) {
    const double error = z - spreader_z;
    const double most = std::abs(error) < slow_m ? kLandingLever : 1.0;
    set("hoist", std::clamp(kHoistGain_per_m * error, -most, most));
    return std::abs(error) < 0.05;
  };
  // along its way at a speed (+ forward, - back), steering on it
  set("direction", 2.0);
  const auto drive_at = [&](double wanted) {
    const double speed = m.forward_mps();
    const bool back = wanted < 0.0 || (wanted == 0.0 && speed < 0.0);
    const core::Vec3 ahead = point_ahead(path_, portal.position, back ? -kLookahead_m : kLookahead_m);
    set("steer", pursuit_steer(portal, m.chassis(), ahead) * (back ? -1.0 : 1.0));
    set("direction", back ? 0.0 : 2.0);
    const double push = (wanted - speed) * (back ? -1.0 : 1.0);
    press("throttle", wanted == 0.0 ? 0.0 : std::clamp(kSpeedGain * push, 0.0, 1.0));
    press("brake", wanted == 0.0 ? 0.6 : std::clamp(-kSpeedGain * push, 0.0, 1.0));
  };
  // to a stop on the line, creeping the last metre; true when stopped there
  const auto drive_to = [&](double stop_along) {
    const double remaining = stop_along - at_along;
    // slower the more the wheel is turned (a box swings out in a fast turn)
    const double cruise =
        kCruise_mps - (kCruise_mps - kCorner_mps) * std::min(1.0, std::abs(m.steering()) / kCornerSteer);
    const double reach = std::min({cruise, std::sqrt(2.0 * kStopping_mps2 * std::abs(remaining)),
                                   std::max(kCreep_mps, std::abs(remaining))});
    drive_at(std::abs(remaining) < kStopped_m ? 0.0 : std::copysign(reach, remaining));
    return std::abs(remaining) < kStopped_m && std::abs(m.forward_mps()) < 0.02;
  };
  // the portal moved so the hanging spreader comes to rest over a point on the line (an operator inching
  // under a swinging load): its speed from the error and the swing, as a pendulum of the falls' length
  const auto catch_swing = [&](double over_along) {
    const double length = std::max(1.0, m.settings().top_frame_m + 0.5 - spreader_z);
    const double omega = std::sqrt(core::kStandardGravity / length);
    const double swing = dot(flat(m.spreader_pose().position) - flat(portal.position), heading);
    const double error = over_along - at_along;
    double wanted = std::clamp(0.25 * omega * error + omega * swing, -kCreep_mps, kCreep_mps);
    if (std::abs(error) > kStopped_m && std::abs(wanted) < kInch_mps && wanted * error >= 0.0)
      wanted = std::copysign(kInch_mps, error);  // the slowest it inches
    drive_at(std::abs(wanted) < 0.01 ? 0.0 : wanted);
    return std::abs(error) < kSteady_m && std::abs(swing) < kSteady_m;
  };
  const auto hold = [&] {
    press("brake", 0.6);
    press("throttle", 0.0);
  };

  if (phase_ == Phase::kApproach || phase_ == Phase::kLand)
    set(box_ref.half_extents_m.x < kTwentyFootHalfLength_m ? "spreader_20" : "spreader_40", 1.0);
  const double box_top = box_pose.position.z + box_ref.half_extents_m.z;
  switch (phase_) {
    case Phase::kApproach: {
      // over the stacks to the box; stopped with the spreader over it
      hoist_to(carry_z - box_height, 0.0);
      if (drive_to(box_along) && spreader_z > box_top + spreader_half_height) enter(Phase::kLand);
      break;
    }
    case Phase::kLand: {
      // down to just over it, the swing caught by inching, then slowly onto its castings
      const bool over = catch_swing(box_along);
      const bool landed = rig.locks().twistlocks().lamps().landed;
      if (spreader_z > box_top + spreader_half_height + kHover_m + 0.05) {
        hoist_to(box_top + spreader_half_height + kHover_m, 1.0);
      } else if (over || landed) {
        set("hoist", landed ? 0.0 : -kLandingLever);
        if (landed) enter(Phase::kLock);
      }
      break;
    }
    case Phase::kLock:
      hold();
      set("lock", std::fmod(now - phase_start_s_, 1.0) < 0.2 ? 1.0 : 0.0);
      if (rig.locks().twistlocks().lamps().locked) enter(Phase::kLift);
      break;
    case Phase::kLift:
      hold();
      if (hoist_to(carry_z, 0.0)) enter(Phase::kCarry);
      break;
    case Phase::kCarry:
      hoist_to(carry_z, 0.0);
      if (drive_to(target_along)) enter(Phase::kSet);
      break;
    case Phase::kSet: {
      // down over the stack, the swing caught, then onto it until it carries the box
      const bool over = catch_swing(target_along);
      const double landed_z = goal.target_m.z + 0.5 * box_height + spreader_half_height;
      if (spreader_z > landed_z + kHover_m + 0.05 || over) hoist_to(landed_z - 0.1, kHover_m + 0.05);
      if (rig.net_load_t() * 1000.0 < 0.1 * world.mass_kg(box_ref.body)) enter(Phase::kUnlock);
      break;
    }
    case Phase::kUnlock:
      hold();
      set("unlock", std::fmod(now - phase_start_s_, 1.0) < 0.2 ? 1.0 : 0.0);
      if (!rig.locks().twistlocks().lamps().locked) enter(Phase::kClear);
      break;
    case Phase::kClear:
      hold();
      if (now - phase_start_s_ > 1.0 && hoist_to(goal.target_m.z + 0.5 * box_height + 1.0, 0.0))
        enter(Phase::kDone);
      break;
    case Phase::kDone:
      hold();
      set("direction", 1.0);
      break;
  }
  return c;
}

}  // namespace harbour::sim
