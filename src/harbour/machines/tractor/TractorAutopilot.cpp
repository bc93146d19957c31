#include "harbour/machines/tractor/TractorAutopilot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harbour/machines/parts/PurePursuit.h"
#include "harbour/machines/tractor/TerminalTractor.h"

namespace harbour::sim {
namespace {

constexpr double kCruise_mps = 3.0;  // 10.8 km/h
constexpr double kCorner_mps = 2.0;  // with the wheel turned more than kCornerSteer
constexpr double kCornerSteer = 0.3;
constexpr double kStopping_mps2 = 0.3;        // the deceleration it plans its stop with
constexpr double kLookahead_m = 5.0;          // at least; 1.5 s of travel at speed
constexpr double kOvershoot_m = 30.0;         // the path goes on past the goal (something to look ahead to)
constexpr double kSpeedGain = 0.4;            // pedal per m/s of speed error
constexpr double kSpeedIntegral_per_s = 0.3;  // pedal per metre short of the wanted speed over time
constexpr double kStanding_mps = 0.05;
constexpr double kZoneShare = 0.8;        // of a zone's speed limit
constexpr double kZoneLookahead_m = 8.0;  // a zone is slowed for this far before the stopping distance
constexpr double kPedalRate_per_s = 0.5;  // how fast a foot moves a pedal (a smooth driver)
// reversing a trailer: walking pace; the axles' path onto the bay's line from this far out; a point this far
// behind the axles to steer for; the hitch angle closes on its aim over kHitchClose_m of travel
constexpr double kReverse_mps = 1.0;
constexpr double kBayEntry_m = 16.0;
constexpr double kReverseLookahead_m = 7.0;
constexpr double kHitchClose_m = 2.5;
constexpr double kMostHitch_rad = 0.6;  // the hitch angle it asks at most (a jack-knife is counted at 1.4)

core::Vec3 flat(core::Vec3 v) {
  v.z = 0.0;
  return v;
}

}  // namespace

std::string TractorAutopilot::why_cannot_drive(const ExerciseSettings& exercise) {
  const auto* tractor = exercise.scenario.machine.get_if<TractorSetup>();
  if (!tractor || !tractor->start.trailer) return "the tractor autopilot drives a tractor with a trailer";
  if (exercise.moves.size() != 1 || !exercise.moves[0].heading_rad)
    return "the exercise has no parking move with a heading for its trailer (exercise.moves)";
  return "";
}

TractorAutopilot::TractorAutopilot(const ExerciseSettings& exercise, DriverDefects defects)
    : exercise_(exercise), defects_(defects), to_load_stop_(exercise.load_stop.has_value()) {
  if (const std::string why = why_cannot_drive(exercise); !why.empty()) throw std::invalid_argument(why);
}

TractorAutopilot::Leg TractorAutopilot::leg() const {
  if (to_load_stop_) return {exercise_.load_stop->trailer_at_m, exercise_.load_stop->heading_rad};
  return {exercise_.moves[0].target_m, *exercise_.moves[0].heading_rad};
}

const char* TractorAutopilot::activity() const {
  switch (phase_) {
    case Phase::kDrive:
      return "drive";
    case Phase::kStop:
      return "stop";
    case Phase::kWaitForLoad:
      return "wait for the load";
    case Phase::kDrop:
      return "drop";
    case Phase::kDone:
      return "done";
  }
  return "";
}

void TractorAutopilot::resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) {
  phase_ = moves_done >= 1 ? Phase::kDone : Phase::kDrive;
  to_load_stop_ = exercise_.load_stop && !simulation.machine().load();
  phase_start_s_ = simulation.time_s();
  planned_ = false;
  take_levers(levers);
}

double TractorAutopilot::trailer_axles_x_m() const {
  const TrailerSettings& trailer = *exercise_.scenario.machine.as<TractorSetup>().start.trailer;
  double sum = 0.0;
  for (const AxleSettings& axle : trailer.wheels.axles)
    sum += axle.x_m;
  return trailer.wheels.axles.empty() ? 0.0 : sum / static_cast<double>(trailer.wheels.axles.size());
}

void TractorAutopilot::plan(const Simulation& simulation, const TerminalTractor& tractor) {
  const Leg goal = leg();
  const core::Pose trailer_pose = simulation.world().pose(tractor.trailer_body());
  reversing_ = dot(flat(goal.target_m - trailer_pose.position), flat(trailer_pose.rotation.column(0))) < 0.0;
  if (reversing_) {
    // the trailer's axles: from where they stand onto the bay's line kBayEntry_m out, along it to where they
    // stand with the trailer's centre on the target, and on
    const core::Vec3 bay{std::cos(goal.heading_rad), std::sin(goal.heading_rad), 0.0};
    const double axles_x = trailer_axles_x_m();
    const core::Vec3 end = flat(goal.target_m) + bay * axles_x;
    path_ = {flat(trailer_pose.to_parent({axles_x, 0, 0})), end + bay * kBayEntry_m, end,
             end - bay * kOvershoot_m};
    planned_ = true;
    return;
  }
  // from its rear axle now, along its heading to the corner on the final line, along that line to where its
  // rear axle stands when the trailer's centre is on the target, and on
  const TractorSettings& s = tractor.settings();
  const core::Pose pose = simulation.world().pose(tractor.body());
  const double rear_x = tractor.chassis().reference_x_m();
  const core::Vec3 start = flat(pose.to_parent({rear_x, 0, 0}));
  const core::Vec3 heading =
      flat(pose.rotation.column(0)) * (1.0 / core::length(flat(pose.rotation.column(0))));
  const core::Vec3 along{std::cos(goal.heading_rad), std::sin(goal.heading_rad), 0.0};
  const TrailerSettings& trailer = *exercise_.scenario.machine.as<TractorSetup>().start.trailer;
  const double trailer_to_rear_axle = trailer.kingpin_m.x + (rear_x - s.hitch_m.x);
  const core::Vec3 end = flat(goal.target_m) + along * trailer_to_rear_axle;
  path_ = {start};
  // the corner: start + t·heading on the line end + u·along
  const double cross_z = heading.x * along.y - heading.y * along.x;
  if (std::abs(cross_z) > 1e-3) {
    const core::Vec3 d = end - start;
    const double t = (d.x * along.y - d.y * along.x) / cross_z;
    if (t > 0.0) path_.push_back(start + heading * t);
  }
  path_.push_back(end);
  path_.push_back(end + along * kOvershoot_m);
  planned_ = true;
}

double TractorAutopilot::remaining_m(const Simulation& simulation, const TerminalTractor& tractor) const {
  const Leg goal = leg();
  const core::Vec3 along{std::cos(goal.heading_rad), std::sin(goal.heading_rad), 0.0};
  return dot(flat(goal.target_m - simulation.world().pose(tractor.trailer_body()).position), along);
}

double TractorAutopilot::reversing_steer(const Simulation& simulation, const TerminalTractor& tractor) const {
  // backing at u with the hitch at the tractor's rear axle: the trailer's heading θ2 turns at (u / L2) sin ψ,
  // the tractor's θ1 at -(u / L1) tan δ, so the hitch angle ψ = θ2 - θ1 runs at
  // (u / L2) sin ψ + (u / L1) tan δ. The trailer's path curves (left +) by κ = sin ψ / L2; pure pursuit of a
  // point behind its axles asks κ = 2 sin α / d, hence the hitch angle's aim, and the steering
  // tan δ = -(L1 / L2) sin ψ - (L1 / kHitchClose_m) (ψ - aim) closes on it
  const TrailerSettings& settings = *exercise_.scenario.machine.as<TractorSetup>().start.trailer;
  const core::Pose trailer = simulation.world().pose(tractor.trailer_body());
  const core::Pose pose = simulation.world().pose(tractor.body());
  const double axles_x = trailer_axles_x_m();
  const core::Vec3 axles = flat(trailer.to_parent({axles_x, 0, 0}));
  const core::Vec3 back = flat(trailer.rotation.column(0)) * -1.0;
  const core::Vec3 to = point_ahead(path_, axles, kReverseLookahead_m) - axles;
  const double alpha = std::atan2(back.x * to.y - back.y * to.x, back.x * to.x + back.y * to.y);
  const double trailer_base = settings.kingpin_m.x - axles_x;
  const double curvature = 2.0 * std::sin(alpha) / std::max(core::length(to), 1.0);
  const double aim =
      std::clamp(std::asin(std::clamp(curvature * trailer_base, -1.0, 1.0)), -kMostHitch_rad, kMostHitch_rad);
  const core::Vec3 x1 = flat(pose.rotation.column(0)), x2 = flat(trailer.rotation.column(0));
  const double hitch = std::atan2(x1.x * x2.y - x1.y * x2.x, x1.x * x2.x + x1.y * x2.y);  // θ2 - θ1
  const double base = tractor.chassis().steer_base_m();
  const double tan_delta = -(base / trailer_base) * std::sin(hitch) - base / kHitchClose_m * (hitch - aim);
  const double steer =
      std::clamp(std::atan(tan_delta) / tractor.chassis().settings().max_steer_rad, -1.0, 1.0);
  return defects_.reverse_steering_wrong ? -steer : steer;
}

scene::Controls TractorAutopilot::decide(const Simulation& simulation, const TerminalTractor& tractor) {
  if (!planned_) plan(simulation, tractor), speed_integral_ = 0.0;
  const scene::ControlTable& table = simulation.control_table();
  scene::Controls c = table.neutral();
  const auto set = [&](const char* label, double value) {
    c.value[static_cast<std::size_t>(table.find(label))] = value;
  };
  // the pedals move as a foot moves them, from where they were
  const double decision_s = static_cast<double>(kDecisionSteps) * Simulation::kStep_s;
  const auto press = [&](const char* label, double value) {
    const auto slot = static_cast<std::size_t>(table.find(label));
    const double was = last_decision().value[slot], most = kPedalRate_per_s * decision_s;
    c.value[slot] = was + std::clamp(value - was, -most, most);
  };
  const double now = simulation.time_s();
  const double speed = reversing_ ? -tractor.forward_mps() : tractor.forward_mps();  // along the way it goes
  set("direction", reversing_ ? 0.0 : 2.0);
  const auto enter = [&](Phase next) {
    phase_ = next;
    phase_start_s_ = now;
  };
  if (phase_ == Phase::kDrive) {
    // pure pursuit: the arc from the rear axle through a point on the path a look-ahead away (reversing: the
    // trailer's axles' arc, through the hitch angle)
    const core::Pose pose = simulation.world().pose(tractor.body());
    const core::Vec3 rear = flat(pose.to_parent({tractor.chassis().reference_x_m(), 0, 0}));
    const core::Vec3 x = flat(pose.rotation.column(0)) * (reversing_ ? -1.0 : 1.0);
    if (reversing_) {
      set("steer", reversing_steer(simulation, tractor));
    } else {
      const core::Vec3 target = point_ahead(path_, rear, std::max(kLookahead_m, 1.5 * std::abs(speed)));
      set("steer", pursuit_steer(pose, tractor.chassis(), target));
    }
    // speed: cruising, slower in corners, and a planned stop with the trailer's centre on its target
    const double remaining =
        reversing_ ? -remaining_m(simulation, tractor) : remaining_m(simulation, tractor);
    double wanted = reversing_                                    ? kReverse_mps
                    : std::abs(tractor.steering()) > kCornerSteer ? kCorner_mps
                                                                  : kCruise_mps;
    // within the speed limit of where it is and of where it will be within its stopping distance
    const core::Vec3 ahead_point = rear + x * (speed * speed / (2.0 * kStopping_mps2) + kZoneLookahead_m);
    for (const SpeedZone& z : exercise_.speed_zones)
      for (const core::Vec3& p : {rear, ahead_point})
        if (p.x >= z.min_x_m && p.x <= z.max_x_m && p.y >= z.min_y_m && p.y <= z.max_y_m)
          wanted = std::min(wanted, kZoneShare * z.limit_kmh / 3.6);
    wanted = std::min(wanted, std::sqrt(2.0 * kStopping_mps2 * std::max(0.0, remaining)));
    // a foot that presses harder while it is short of speed (uphill, a heavy trailer): proportional and
    // integral, the integral held while the pedal is at its stop
    const double error = wanted - speed;
    const double throttle = kSpeedGain * error + speed_integral_;
    if ((throttle < 1.0 || error < 0.0) && (throttle > 0.0 || error > 0.0))
      speed_integral_ = std::max(0.0, speed_integral_ + kSpeedIntegral_per_s * error * decision_s);
    press("throttle", std::clamp(throttle, 0.0, 1.0));
    press("brake", std::clamp(-kSpeedGain * error - 0.05, 0.0, 1.0));
    if (remaining <= 0.0) enter(Phase::kStop);
  } else if (phase_ == Phase::kStop) {
    press("brake", 0.6);
    if (std::abs(speed) < kStanding_mps && now - phase_start_s_ > 1.0)
      enter(to_load_stop_ ? Phase::kWaitForLoad : Phase::kDrop);
  } else if (phase_ == Phase::kWaitForLoad) {
    // standing under the crane until the box is on, then on to the move's target
    press("brake", 0.6);
    if (tractor.load()) {
      to_load_stop_ = false;
      planned_ = false;
      enter(Phase::kDrive);
    }
  } else if (phase_ == Phase::kDrop) {
    // a press, then the plate lowers and the jaw opens
    press("brake", 0.6);
    set("couple", now - phase_start_s_ < 0.2 ? 1.0 : 0.0);
    if (!tractor.coupled()) enter(Phase::kDone);
  } else {
    press("brake", 0.6);
    set("direction", 1.0);  // neutral
  }
  return c;
}

}  // namespace harbour::sim
