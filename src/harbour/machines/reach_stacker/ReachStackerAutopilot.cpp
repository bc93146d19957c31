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

struct LaneLine {
  core::Vec3 start_m, along;
};

// The stacks on the lane's line between where it carries the box from (`from_along`) and the target.
StacksInTheWay stacks_in_the_way(const Simulation& simulation, const ContainerRef& box, const LaneLine& lane,
                                 double from_along, double target_along) {
  const core::Vec3 lane_left{-lane.along.y, lane.along.x, 0.0};
  StacksInTheWay stacks{target_along - box.half_extents_m.y, 0.0};
  for (const ContainerRef& other : simulation.liftables()) {
    if (other.body == box.body) continue;
    const core::Pose p = simulation.world().pose(other.body);
    const double along = dot(flat(p.position) - lane.start_m, lane.along);
    if (along >= target_along - 0.5 || along <= from_along ||
        std::abs(dot(flat(p.position) - lane.start_m, lane_left)) > kOnTheLine_m)
      continue;
    stacks.nearest_face_along_m = std::min(stacks.nearest_face_along_m, along - other.half_extents_m.y);
    stacks.highest_top_m = std::max(stacks.highest_top_m, p.position.z + other.half_extents_m.z);
  }
  return stacks;
}

// One decision's levers and the motions it is made of: the pedals, the wheel along a path, the boom's head
// towards a goal, the spreader squared on a box.
class Decision {
 public:
  Decision(const Simulation& simulation, const ReachStacker& m, const scene::Controls& last)
      : simulation_(simulation),
        m_(m),
        table_(simulation.control_table()),
        last_(last),
        chassis_(simulation.world().pose(m.body())),
        controls_(table_.neutral()) {}

  const core::Pose& chassis() const { return chassis_; }
  const scene::Controls& controls() const { return controls_; }

  void set(const char* label, double value) {
    controls_.value[static_cast<std::size_t>(table_.find(label))] = value;
  }
  // a pedal moves as a foot moves it, from where it was
  void press(const char* label, double value) {
    const auto slot = static_cast<std::size_t>(table_.find(label));
    const double was = last_.value[slot];
    const double most = kPedalRate_per_s * static_cast<double>(DecidingPilot<ReachStacker>::kDecisionSteps) *
                        Simulation::kStep_s;
    controls_.value[slot] = was + std::clamp(value - was, -most, most);
  }
  void hold() {
    press("brake", 0.6);
    press("throttle", 0.0);
  }
  // along `path` to a stop `remaining_m` ahead; true once stopped there
  bool drive(const std::vector<core::Vec3>& path, double remaining_m, double cruise_mps) {
    const core::Vec3 reference = flat(chassis_.to_parent({m_.chassis().reference_x_m(), 0, 0}));
    const double steer = pursuit_steer(chassis_, m_.chassis(), point_ahead(path, reference, kLookahead_m));
    set("steer", steer);
    // slower the more the wheel is turned (laden, a reach stacker tips sideways in a fast tight turn)
    const double cruise =
        std::min(cruise_mps,
                 kCruise_mps - (kCruise_mps - kCorner_mps) * std::min(1.0, std::abs(steer) / kCornerSteer));
    const double wanted = std::min(cruise, std::sqrt(2.0 * kStopping_mps2 * std::max(0.0, remaining_m)));
    const double error = wanted - m_.forward_mps();
    press("throttle", std::clamp(kSpeedGain * error, 0.0, 1.0));
    press("brake", remaining_m <= 0.0 ? 0.6 : std::clamp(-kSpeedGain * error, 0.0, 1.0));
    return remaining_m <= 0.0 && std::abs(m_.forward_mps()) < 0.05;
  }
  // the boom's head towards a goal; true when it is there
  bool head_to(const core::Vec3& head_goal, double speed_mps) {
    const Levers l = head_levers(simulation_, m_, head_goal, speed_mps);
    set("boom", l.boom);
    set("telescope", l.telescope);
    return std::abs(dot(flat(head_goal - m_.head_m()), forward())) < kAligned_m &&
           std::abs(head_goal.z - m_.head_m().z) < 0.05;
  }
  // the spreader squared on a box below the head (side-shift and rotation); true when it is square
  bool square_over(const core::Vec3& centre, const core::Vec3& length_axis) {
    const ReachStackerSettings& s = m_.settings();
    const core::Pose spreader = m_.spreader_pose();
    const core::Vec3 left = unit(flat(chassis_.rotation.column(1)));
    const double lateral = dot(flat(centre - spreader.position), left);
    set("side_shift", std::clamp(lateral / (0.5 * s.side_shift.max_speed_mps), -1.0, 1.0));
    const core::Vec3 a = flat(spreader.rotation.column(1)), b = flat(length_axis);
    const double skew =
        std::remainder(std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y), std::numbers::pi);
    set("rotate", std::clamp(skew / (0.5 * s.rotate.max_speed_mps), -1.0, 1.0));
    return std::abs(lateral) < kAligned_m && std::abs(skew) < kAlignedRad;
  }
  // the spreader hangs under the head
  bool plumb() const {
    return std::abs(dot(flat(m_.spreader_pose().position - m_.head_m()), forward())) < kAligned_m;
  }

 private:
  core::Vec3 forward() const { return unit(flat(chassis_.rotation.column(0))); }

  const Simulation& simulation_;
  const ReachStacker& m_;
  const scene::ControlTable& table_;
  const scene::Controls& last_;
  const core::Pose chassis_;
  scene::Controls controls_;
};

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

StacksInTheWay ReachStackerAutopilot::stacks_before_target(const Simulation& simulation) const {
  const double target_along = dot(flat(exercise_.moves[0].target_m) - lane_start_m_, lane_along_);
  const double picked_along =
      dot(flat(exercise_.scenario.containers[box_index_].pose.position) - lane_start_m_, lane_along_);
  const double from_along = carry_path_.empty() ? picked_along : 0.0;  // on a route: from its last point
  return stacks_in_the_way(simulation, simulation.liftables()[box_index_], {lane_start_m_, lane_along_},
                           from_along, target_along);
}

void ReachStackerAutopilot::take_route_from(const core::Vec3& where_m) {
  // on along the route, then the line from its last point to the target
  carry_path_ = {where_m};
  carry_path_.insert(carry_path_.end(), exercise_.route_m.begin(), exercise_.route_m.end());
  lane_start_m_ = exercise_.route_m.back();
  lane_along_ = unit(flat(exercise_.moves[0].target_m) - lane_start_m_);
}

scene::Controls ReachStackerAutopilot::decide(const Simulation& simulation, const ReachStacker& m) {
  Decision d(simulation, m, last_decision());
  const double now = simulation.time_s();
  const auto enter = [&](Phase next) {
    phase_ = next;
    phase_start_s_ = now;
  };
  const physics::PhysicsWorld& world = simulation.world();
  const ReachStackerSettings& s = m.settings();
  const MoveGoal& goal = exercise_.moves[0];
  const ContainerRef& box_ref = simulation.liftables()[box_index_];
  const double box_height = 2.0 * box_ref.half_extents_m.z;
  const core::Vec3 front_axle = flat(d.chassis().to_parent({tipping_axle_x_m(s), 0, 0}));
  const double at_along = dot(front_axle - lane_start_m_, lane_along_);

  const StacksInTheWay stacks = stacks_before_target(simulation);
  // the front axle's stop, along the lane
  const double final_stop = stacks.nearest_face_along_m - kTyreClearance_m - s.chassis.tyre.radius_m;

  // driving: along the lane's line (or the route and then the target's line) to a stop, the brake held while
  // the boom works
  d.set("direction", 2.0);
  const auto drive_to = [&](double stop_along, double cruise_mps) {
    std::vector<core::Vec3> path = carry_path_;
    if (path.empty()) path.push_back(lane_start_m_);
    path.push_back(lane_start_m_ + lane_along_ * (stop_along + 50.0));
    return d.drive(path, stop_along - at_along, cruise_mps);
  };

  const core::Pose box_pose = world.pose(box_ref.body);
  const double box_top = box_pose.position.z + box_ref.half_extents_m.z;
  // the spreader's length for the box: its button held until it is there
  if (phase_ == Phase::kApproach || phase_ == Phase::kPick) {
    const bool twenty = box_ref.half_extents_m.x < kTwentyFootHalfLength_m;
    d.set(twenty ? "spreader_20" : "spreader_40", 1.0);
  }
  switch (phase_) {
    case Phase::kApproach: {
      // to where the box lies at the first row's reach, the spreader brought over it on the way
      // (raised over the box's top before it reaches out: a box on a truck stands higher than the head)
      const double stop = dot(flat(box_pose.position) - lane_start_m_, lane_along_) - s.row_reach_m.front();
      const double hover_z = head_z_over(m, box_top, kHover_m);
      core::Vec3 goal_head = m.head_m().z > hover_z - kRaisedFirst_m ? box_pose.position : m.head_m();
      goal_head.z = hover_z;
      d.head_to(goal_head, kHeadSpeed_mps);
      if (drive_to(stop, kCruise_mps)) enter(Phase::kPick);
      break;
    }
    case Phase::kPick: {
      d.hold();
      const bool square = d.square_over(box_pose.position, box_pose.rotation.column(0));
      core::Vec3 goal_head = box_pose.position;
      goal_head.z = head_z_over(m, box_top, kHover_m);
      const bool over = d.head_to(goal_head, kHeadSpeed_mps);
      if (over && square && d.plumb()) enter(Phase::kLock);
      break;
    }
    case Phase::kLock: {
      // down onto the castings slowly, then the locks
      d.hold();
      d.square_over(box_pose.position, box_pose.rotation.column(0));
      core::Vec3 goal_head = box_pose.position;
      goal_head.z = head_z_over(m, box_top, -0.05);
      if (!m.lamps().landed) d.head_to(goal_head, kLanding_mps);
      d.set("lock", m.lamps().landed && std::fmod(now - phase_start_s_, 1.0) < 0.2 ? 1.0 : 0.0);
      if (m.lamps().locked) enter(Phase::kLift);
      break;
    }
    case Phase::kLift: {
      // up off what it stood on (a truck's chassis: the truck leaves), kept at its reach; it waits for the
      // way to clear
      d.hold();
      const ContainerPlacement& picked = exercise_.scenario.containers[box_index_];
      const double picked_bottom = picked.pose.position.z - picked.half_extents_m.z;
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, std::max(kCarryClearance_m, picked_bottom + kLiftOff_m) + box_height, 0.0);
      if (d.head_to(goal_head, kHeadSpeed_mps) && way_clear(simulation)) {
        if (!exercise_.route_m.empty())
          take_route_from(flat(d.chassis().to_parent({m.chassis().reference_x_m(), 0, 0})));
        enter(Phase::kCarry);
      }
      break;
    }
    case Phase::kCarry: {
      // down to carrying height (off a truck) on the way
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, kCarryClearance_m + box_height, 0.0);
      d.head_to(goal_head, kHeadSpeed_mps);
      if (drive_to(final_stop - kRaiseShort_m, kCruise_mps)) enter(Phase::kRaise);
      break;
    }
    case Phase::kRaise: {
      d.hold();
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, stacks.highest_top_m + kCarryClearance_m + box_height, 0.0);
      if (d.head_to(goal_head, kHeadSpeed_mps)) enter(Phase::kCreep);
      break;
    }
    case Phase::kCreep:
      if (drive_to(final_stop, kCreep_mps)) enter(Phase::kReach);
      break;
    case Phase::kReach: {
      // out over the target, square on it
      d.hold();
      const core::Vec3 along_box = {std::cos(goal.heading_rad.value_or(0.0)),
                                    std::sin(goal.heading_rad.value_or(0.0)), 0.0};
      const bool square =
          d.square_over(goal.target_m, goal.heading_rad ? along_box : box_pose.rotation.column(0));
      core::Vec3 goal_head = goal.target_m;
      goal_head.z = head_z_over(m, goal.target_m.z - box_height / 2, kHover_m + box_height);
      if (d.head_to(goal_head, kHeadSpeed_mps) && square && d.plumb()) enter(Phase::kSet);
      break;
    }
    case Phase::kSet: {
      // down until the stack carries it
      d.hold();
      core::Vec3 goal_head = goal.target_m;
      goal_head.z = head_z_over(m, goal.target_m.z - box_height / 2, box_height - 0.1);
      d.head_to(goal_head, kLanding_mps);
      if (m.measured_load_kg() < 0.1 * world.mass_kg(box_ref.body)) enter(Phase::kUnlock);
      break;
    }
    case Phase::kUnlock: {
      // the spreader let down on the box until the head carries only the spreader (the chassis rises as the
      // load leaves it), then the locks
      d.hold();
      core::Vec3 goal_head = goal.target_m;
      goal_head.z = head_z_over(m, goal.target_m.z - box_height / 2, box_height - 0.2);
      d.head_to(goal_head, kLanding_mps);
      d.set("unlock", std::fmod(now - phase_start_s_, 1.0) < 0.2 ? 1.0 : 0.0);
      if (!m.lamps().locked) enter(Phase::kClear);
      break;
    }
    case Phase::kClear: {
      d.hold();
      core::Vec3 goal_head = m.head_m();
      goal_head.z = head_z_over(m, goal.target_m.z + box_height / 2, 0.8);
      if (now - phase_start_s_ > 1.0 && d.head_to(goal_head, 0.3)) enter(Phase::kDone);
      break;
    }
    case Phase::kDone:
      d.hold();
      d.set("direction", 1.0);
      break;
  }
  return d.controls();
}

}  // namespace harbour::sim
