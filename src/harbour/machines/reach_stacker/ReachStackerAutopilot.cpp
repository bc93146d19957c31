#include "harbour/machines/reach_stacker/ReachStackerAutopilot.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "harbour/machines/parts/PurePursuit.h"
#include "harbour/machines/reach_stacker/ReachStacker.h"

namespace harbour::sim {
namespace {

constexpr double kCruise_mps = 2.0;  // laden or not, in a stacking lane
constexpr double kCorner_mps = 1.0;  // with the wheel turned kCornerSteer or more
constexpr double kCornerSteer = 0.3;
constexpr double kLiftOff_m = 0.3;     // the box lifted this far off what it stood on before it is carried
constexpr double kTruckGone_m = 20.0;  // a truck this far from its stop has left the way clear
constexpr double kTwentyFootHalfLength_m = 4.0;  // a box shorter than this takes the spreader at 20 ft
constexpr double kRaisedFirst_m = 0.2;           // the head this near its hover height before it reaches out
constexpr double kOnTheLine_m = 2.0;             // stacks this close to the target's line stand in the way
constexpr double kCreep_mps = 0.5;
constexpr double kStopping_mps2 = 0.3;  // the deceleration it plans its stops with
constexpr double kSpeedGain = 0.5;      // pedal per m/s of speed error
constexpr double kLookahead_m = 6.0;
constexpr double kPedalRate_per_s = 0.5;  // how fast a foot moves a pedal (a smooth driver)
constexpr double kHeadGain_per_s = 0.8;   // the head's wanted speed per metre from its goal
constexpr double kHeadSpeed_mps = 0.6;
constexpr double kLanding_mps = 0.06;  // the head's speed down onto a box (no impact counted below 0.1 m/s)
constexpr double kHover_m = 0.3;       // above where it lands before it comes down
constexpr double kAligned_m = 0.015, kAlignedRad = 0.004;
constexpr double kCarryClearance_m = 0.5;  // the box's bottom over the ground, and over stacks it passes
constexpr double kRaiseShort_m = 4.0;      // it stops this short of the stacks to raise the box over them
constexpr double kTyreClearance_m = 0.55;  // its front tyres' clearance to the first row's boxes at a stop

core::Vec3 flat(core::Vec3 v) {
  v.z = 0.0;
  return v;
}

core::Vec3 unit(core::Vec3 v) {
  return v * (1.0 / core::length(v));
}

struct Levers {
  double boom = 0.0, telescope = 0.0;
};

// The lift and extension levers that move the boom's head towards `goal` (in the boom's plane: along the
// chassis's heading and up) at most `speed_mps`: the head's wanted velocity resolved along the boom (the
// extension) and across it (the boom's angle times its length).
Levers head_levers(const Simulation& simulation, const ReachStacker& m, const core::Vec3& goal,
                   double speed_mps) {
  const core::Pose chassis = simulation.world().pose(m.body());
  const core::Vec3 forward = unit(flat(chassis.rotation.column(0)));
  const core::Vec3 head = m.head_m();
  const double along = dot(flat(goal - head), forward), up = goal.z - head.z;
  double v_along = kHeadGain_per_s * along, v_up = kHeadGain_per_s * up;
  const double v = std::hypot(v_along, v_up);
  if (v > speed_mps) v_along *= speed_mps / v, v_up *= speed_mps / v;
  const double angle = m.boom_angle_rad() + std::asin(std::clamp(chassis.rotation.column(0).z, -1.0, 1.0));
  const double length = m.settings().boom_length_m + m.extension_m();
  const double extend = v_along * std::cos(angle) + v_up * std::sin(angle);
  const double turn = (-v_along * std::sin(angle) + v_up * std::cos(angle)) / length;
  Levers l{turn / m.settings().luff.max_speed_mps, extend / m.settings().telescope.max_speed_mps};
  const double most = std::max({1.0, std::abs(l.boom), std::abs(l.telescope)});
  return {l.boom / most, l.telescope / most};
}

// The head's height that puts the spreader's underside `above_m` over a box top at `top_z`.
double head_z_over(const ReachStacker& m, double top_z, double above_m) {
  return top_z + above_m + 0.5 * m.settings().spreader.height_m + m.settings().head_drop_m;
}

}  // namespace

std::string ReachStackerAutopilot::why_cannot_drive(const ExerciseSettings& exercise) {
  const auto* setup = exercise.scenario.machine.get_if<ReachStackerSetup>();
  if (!setup) return "the reach stacker autopilot drives a reach stacker";
  if (exercise.moves.size() != 1) return "the reach stacker autopilot makes one move (exercise.moves)";
  const core::Vec3 along{std::cos(setup->start.heading_rad), std::sin(setup->start.heading_rad), 0.0};
  const core::Vec3 left{-along.y, along.x, 0.0};
  const MoveGoal& goal = exercise.moves[0];
  const ContainerPlacement* box = nullptr;
  for (const ContainerPlacement& c : exercise.scenario.containers)
    if (c.id == goal.container_id) box = &c;
  if (!box) return "the move's box is not in the exercise";
  const core::Vec3 to_box = flat(box->pose.position - setup->start.position_m);
  if (std::abs(dot(to_box, left)) > 0.5 || dot(to_box, along) <= 0.0)
    return "the reach stacker autopilot picks the box ahead on its line";
  if (!exercise.route_m.empty()) return "";  // it drives the route to the target
  const core::Vec3 to_target = flat(goal.target_m - setup->start.position_m);
  if (std::abs(dot(to_target, left)) > 0.5 || dot(to_target, along) <= dot(to_box, along))
    return "the reach stacker autopilot drives along one lane without a route (exercise.route_m): the target "
           "further along the box's line";
  return "";
}

ReachStackerAutopilot::ReachStackerAutopilot(const ExerciseSettings& exercise, DriverDefects defects)
    : exercise_(exercise), defects_(defects) {
  if (defects_.ignore_route) exercise_.route_m.clear();
  if (const std::string why = why_cannot_drive(exercise_); !why.empty()) throw std::invalid_argument(why);
  const auto& setup = exercise.scenario.machine.as<ReachStackerSetup>();
  lane_start_m_ = flat(setup.start.position_m);
  lane_along_ = {std::cos(setup.start.heading_rad), std::sin(setup.start.heading_rad), 0.0};
  while (exercise.scenario.containers[box_index_].id != exercise.moves[0].container_id)
    ++box_index_;
}

const char* ReachStackerAutopilot::activity() const {
  constexpr const char* kNames[] = {"approach", "pick",  "lock", "lift",   "carry", "raise",
                                    "creep",    "reach", "set",  "unlock", "clear", "done"};
  return kNames[static_cast<int>(phase_)];
}

void ReachStackerAutopilot::resume(const Simulation& simulation, int moves_done,
                                   const scene::Controls& levers) {
  const auto* machine = dynamic_cast<const ReachStacker*>(&simulation.machine());
  phase_ = moves_done >= 1 ? Phase::kDone : machine && machine->held_item() ? Phase::kLift : Phase::kApproach;
  phase_start_s_ = simulation.time_s();
  take_levers(levers);
}

bool ReachStackerAutopilot::way_clear(const Simulation& simulation) const {
  const TruckLane* trucks = simulation.trucks();
  const TruckLaneSettings& lane = exercise_.scenario.trucks;
  for (int k = 0; trucks && k < lane.trucks; ++k)
    if (std::abs(trucks->truck_y(k) - lane.stop_y_m) < kTruckGone_m) return false;
  return true;
}

scene::Controls ReachStackerAutopilot::decide(const Simulation& simulation, const ReachStacker& m) {
  const scene::ControlTable& table = simulation.control_table();
  scene::Controls c = table.neutral();
  const auto set = [&](const char* label, double value) {
    c.value[static_cast<std::size_t>(table.find(label))] = value;
  };
  const double now = simulation.time_s();
  // the pedals move as a foot moves them, from where they were
  const auto press = [&](const char* label, double value) {
    const auto slot = static_cast<std::size_t>(table.find(label));
    const double was = last_decision().value[slot];
    const double most = kPedalRate_per_s * static_cast<double>(kDecisionSteps) * Simulation::kStep_s;
    c.value[slot] = was + std::clamp(value - was, -most, most);
  };
  const auto enter = [&](Phase next) {
    phase_ = next;
    phase_start_s_ = now;
  };
  const physics::PhysicsWorld& world = simulation.world();
  const ReachStackerSettings& s = m.settings();
  const MoveGoal& goal = exercise_.moves[0];
  const ContainerRef* box_ref = &simulation.liftables()[box_index_];
  const physics::BodyId box = box_ref->body;
  const double box_height = 2.0 * box_ref->half_extents_m.z;
  const core::Pose chassis = world.pose(m.body());
  const core::Vec3 front_axle = flat(chassis.to_parent({tipping_axle_x_m(s), 0, 0}));
  const double at_along = dot(front_axle - lane_start_m_, lane_along_);
  const double tyre_front = s.chassis.tyre.radius_m;

  // the stacks between the box and its target: the nearest face it stops short of and the highest top it
  // raises the box over
  const double target_along = dot(flat(goal.target_m) - lane_start_m_, lane_along_);
  const double picked_along =
      dot(flat(exercise_.scenario.containers[box_index_].pose.position) - lane_start_m_, lane_along_);
  const double from_along = carry_path_.empty() ? picked_along : 0.0;  // on a route: from its last point
  const core::Vec3 lane_left{-lane_along_.y, lane_along_.x, 0.0};
  double nearest_face = target_along - box_ref->half_extents_m.y, highest_top = 0.0;
  for (const ContainerRef& other : simulation.liftables()) {
    if (other.body == box) continue;
    const core::Pose p = world.pose(other.body);
    const double along = dot(flat(p.position) - lane_start_m_, lane_along_);
    if (along >= target_along - 0.5 || along <= from_along ||
        std::abs(dot(flat(p.position) - lane_start_m_, lane_left)) > kOnTheLine_m)
      continue;
    nearest_face = std::min(nearest_face, along - other.half_extents_m.y);
    highest_top = std::max(highest_top, p.position.z + other.half_extents_m.z);
  }
  const double final_stop = nearest_face - kTyreClearance_m - tyre_front;  // the front axle's, along the lane

  // driving: along the lane's line to a stop, the brake held while the boom works
  set("direction", 2.0);
  const auto drive_to = [&](double stop_along, double cruise_mps) {
    // along the lane's line, or the route and then the target's line
    std::vector<core::Vec3> path = carry_path_;
    if (path.empty()) path.push_back(lane_start_m_);
    path.push_back(lane_start_m_ + lane_along_ * (stop_along + 50.0));
    const core::Vec3 reference = flat(chassis.to_parent({m.chassis().reference_x_m(), 0, 0}));
    const double steer = pursuit_steer(chassis, m.chassis(), point_ahead(path, reference, kLookahead_m));
    set("steer", steer);
    const double remaining = stop_along - at_along;
    // slower the more the wheel is turned (laden, a reach stacker tips sideways in a fast tight turn)
    const double cruise =
        std::min(cruise_mps,
                 kCruise_mps - (kCruise_mps - kCorner_mps) * std::min(1.0, std::abs(steer) / kCornerSteer));
    const double wanted = std::min(cruise, std::sqrt(2.0 * kStopping_mps2 * std::max(0.0, remaining)));
    const double error = wanted - m.forward_mps();
    press("throttle", std::clamp(kSpeedGain * error, 0.0, 1.0));
    press("brake", remaining <= 0.0 ? 0.6 : std::clamp(-kSpeedGain * error, 0.0, 1.0));
    return remaining <= 0.0 && std::abs(m.forward_mps()) < 0.05;
  };
  const auto hold = [&] {
    press("brake", 0.6);
    press("throttle", 0.0);
  };
  // the boom's head towards a goal, and the spreader squared on a box below it (side-shift and rotation);
  // true when it is there and square
  const auto head_to = [&](const core::Vec3& head_goal, double speed_mps) {
    const Levers l = head_levers(simulation, m, head_goal, speed_mps);
    set("boom", l.boom);
    set("telescope", l.telescope);
    const core::Vec3 forward = unit(flat(chassis.rotation.column(0)));
    return std::abs(dot(flat(head_goal - m.head_m()), forward)) < kAligned_m &&
           std::abs(head_goal.z - m.head_m().z) < 0.05;
  };
  const auto square_over = [&](const core::Vec3& centre, const core::Vec3& length_axis) {
    const core::Pose spreader = m.spreader_pose();
    const core::Vec3 left = unit(flat(chassis.rotation.column(1)));
    const double lateral = dot(flat(centre - spreader.position), left);
    set("side_shift", std::clamp(lateral / (0.5 * s.side_shift.max_speed_mps), -1.0, 1.0));
    const core::Vec3 a = flat(spreader.rotation.column(1)), b = flat(length_axis);
    const double skew =
        std::remainder(std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y), std::numbers::pi);
    set("rotate", std::clamp(skew / (0.5 * s.rotate.max_speed_mps), -1.0, 1.0));
    return std::abs(lateral) < kAligned_m && std::abs(skew) < kAlignedRad;
  };
  const auto plumb = [&] {
    return std::abs(dot(flat(m.spreader_pose().position - m.head_m()),
                        unit(flat(chassis.rotation.column(0))))) < kAligned_m;
  };

  const core::Pose box_pose = world.pose(box);
  const double box_top = box_pose.position.z + box_ref->half_extents_m.z;
  // the spreader's length for the box: its button held until it is there
  if (phase_ == Phase::kApproach || phase_ == Phase::kPick) {
    const bool twenty = box_ref->half_extents_m.x < kTwentyFootHalfLength_m;
    set(twenty ? "spreader_20" : "spreader_40", 1.0);
  }
  switch (phase_) {
    case Phase::kApproach: {
      // to where the box lies at the first row's reach, the spreader brought over it on the way
      // (raised over the box's top before it reaches out: a box on a truck stands higher than the head)
      const double stop = dot(flat(box_pose.position) - lane_start_m_, lane_along_) - s.row_reach_m.front();
      const double hover_z = head_z_over(m, box_top, kHover_m);
      core::Vec3 goal_head = m.head_m().z > hover_z - kRaisedFirst_m ? box_pose.position : m.head_m();
      goal_head.z = hover_z;
      head_to(goal_head, kHeadSpeed_mps);
      if (drive_to(stop, kCruise_mps)) enter(Phase::kPick);
      break;
    }
    case Phase::kPick: {
      hold();
      const bool square = square_over(box_pose.position, box_pose.rotation.column(0));
      core::Vec3 goal_head = box_pose.position;
      goal_head.z = head_z_over(m, box_top, kHover_m);
      const bool over = head_to(goal_head, kHeadSpeed_mps);
      if (over && square && plumb()) enter(Phase::kLock);
      break;
    }
    case Phase::kLock: {
      // down onto the castings slowly, then the locks
      hold();
      square_over(box_pose.position, box_pose.rotation.column(0));
      core::Vec3 goal_head = box_pose.position;
      goal_head.z = head_z_over(m, box_top, -0.05);
      if (!m.lamps().landed) head_to(goal_head, kLanding_mps);
      set("lock", m.lamps().landed && std::fmod(now - phase_start_s_, 1.0) < 0.2 ? 1.0 : 0.0);
      if (m.lamps().locked) enter(Phase::kLift);
      break;
    }
    case Phase::kLift: {
      // up off what it stood on (a truck's chassis: the truck leaves), kept at its reach; it waits for the
      // way to clear
      hold();
      const ContainerPlacement& picked = exercise_.scenario.containers[box_index_];
      const double picked_bottom = picked.pose.position.z - picked.half_extents_m.z;
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, std::max(kCarryClearance_m, picked_bottom + kLiftOff_m) + box_height, 0.0);
      if (head_to(goal_head, kHeadSpeed_mps) && way_clear(simulation)) {
        if (!exercise_.route_m.empty()) {
          // on along the route, then the line from its last point to the target
          carry_path_ = {flat(chassis.to_parent({m.chassis().reference_x_m(), 0, 0}))};
          carry_path_.insert(carry_path_.end(), exercise_.route_m.begin(), exercise_.route_m.end());
          lane_start_m_ = exercise_.route_m.back();
          lane_along_ = unit(flat(goal.target_m) - lane_start_m_);
        }
        enter(Phase::kCarry);
      }
      break;
    }
    case Phase::kCarry: {
      // down to carrying height (off a truck) on the way
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, kCarryClearance_m + box_height, 0.0);
      head_to(goal_head, kHeadSpeed_mps);
      if (drive_to(final_stop - kRaiseShort_m, kCruise_mps)) enter(Phase::kRaise);
      break;
    }
    case Phase::kRaise: {
      hold();
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, highest_top + kCarryClearance_m + box_height, 0.0);
      if (head_to(goal_head, kHeadSpeed_mps)) enter(Phase::kCreep);
      break;
    }
    case Phase::kCreep:
      if (drive_to(final_stop, kCreep_mps)) enter(Phase::kReach);
      break;
    case Phase::kReach: {
      // out over the target, square on it
      hold();
      const core::Vec3 along_box = {std::cos(goal.heading_rad.value_or(0.0)),
                                    std::sin(goal.heading_rad.value_or(0.0)), 0.0};
      const bool square =
          square_over(goal.target_m, goal.heading_rad ? along_box : box_pose.rotation.column(0));
      core::Vec3 goal_head = goal.target_m;
      goal_head.z = head_z_over(m, goal.target_m.z - box_height / 2, kHover_m + box_height);
      if (head_to(goal_head, kHeadSpeed_mps) && square && plumb()) enter(Phase::kSet);
      break;
    }
    case Phase::kSet: {
      // down until the stack carries it
      hold();
      core::Vec3 goal_head = goal.target_m;
      goal_head.z = head_z_over(m, goal.target_m.z - box_height / 2, box_height - 0.1);
      head_to(goal_head, kLanding_mps);
      if (m.measured_load_kg() < 0.1 * world.mass_kg(box)) enter(Phase::kUnlock);
      break;
    }
    case Phase::kUnlock: {
      // the spreader let down on the box until the head carries only the spreader (the chassis rises as the
      // load leaves it), then the locks
      hold();
      core::Vec3 goal_head = goal.target_m;
      goal_head.z = head_z_over(m, goal.target_m.z - box_height / 2, box_height - 0.2);
      head_to(goal_head, kLanding_mps);
      set("unlock", std::fmod(now - phase_start_s_, 1.0) < 0.2 ? 1.0 : 0.0);
      if (!m.lamps().locked) enter(Phase::kClear);
      break;
    }
    case Phase::kClear: {
      hold();
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, goal.target_m.z + box_height / 2, 0.8);
      if (now - phase_start_s_ > 1.0 && head_to(goal_head, 0.3)) enter(Phase::kDone);
      break;
    }
    case Phase::kDone:
      hold();
      set("direction", 1.0);
      break;
  }
  return c;
}

}  // namespace harbour::sim
