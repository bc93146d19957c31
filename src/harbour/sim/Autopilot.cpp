#include "harbour/sim/Autopilot.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace harbour::sim {
namespace {

constexpr double kTravelHeight_m = 22.0;  // spreader centre while travelling: clears the vessel's stack
constexpr double kCruiseLever = 0.75;     // travel at three quarters of full speed
constexpr double kSlowZone_m = 1.5;       // lower slowly over the last metre and a half
constexpr double kSlowLever = 0.08;       // 0.12 m/s at the spreader on the STS hoist
constexpr double kPosition_tolerance_m = 0.03;
constexpr double kSettledSwingSpeed_mps = 0.05;  // the swing has slowed enough to start lowering
constexpr double kButton_s = 0.1;
constexpr double kSlacken_s = 0.6;
constexpr double kHorn_s = 1.0;  // the horn sounds this long before the gantry travels

}  // namespace

Autopilot::Autopilot(const ExerciseSettings& exercise, OperatorDefects defects)
    : exercise_(exercise), defects_(defects) {}

std::size_t Autopilot::goal_index(const Simulation& simulation) const {
  const auto& items = simulation.scenario().containers;
  for (std::size_t n = 0; n < items.size(); ++n)
    if (items[n].id == exercise_.moves[goal_].container_id) return n;
  throw std::logic_error("exercise move names no scenario item");  // the loader checks it
}

double Autopilot::goal_half_height(const Simulation& simulation) const {
  return simulation.scenario().containers[goal_index(simulation)].half_extents_m.z;
}

core::Vec3 Autopilot::source(const Simulation& simulation) const {
  return simulation.world().pose(simulation.container_body(goal_index(simulation))).position;
}

std::array<bool, 4> Autopilot::flippers(const Simulation& simulation) const {
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

void Autopilot::start_travel(const core::Vec3& to, double gantry_y, double now) {
  trolley_ = {to.x, 0.0, now, false, 0.0, -1.0};
  // a gantry travel waits for the horn
  const bool gantry_travels = std::abs(to.y - gantry_y) > kPosition_tolerance_m;
  gantry_ = {to.y, 0.0, gantry_travels ? now + kHorn_s : now, false, 0.0, -1.0};
}

double Autopilot::axis_lever(AxisMove& m, double position, double max_speed, double period,
                             double now) const {
  // trapezoid in the lever: ramp up over exactly one period (so the swing it starts ends with the ramp),
  // brake over one period when the remaining distance equals what a linear ramp-down covers (v T / 2), then
  // creep onto the target. A move too short to reach cruise ramps to a lower top, still over one period.
  if (now < m.ramp_start) return 0.0;  // not started yet
  const double error = m.target - position;
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
  // creep: proportional, slow enough not to swing the load
  return std::abs(error) > kPosition_tolerance_m ? std::clamp(error * 0.05, -0.02, 0.02) : 0.0;
}

void Autopilot::resume(const Simulation& simulation, int moves_done) {
  goal_ = static_cast<std::size_t>(std::max(0, moves_done));
  phase_ = Phase::kRaise;
  phase_start_ = simulation.time_s();
  carrying_ = !done() && simulation.crane().locked_container() ==
                             std::optional(simulation.container_body(goal_index(simulation)));
}

Inputs Autopilot::next(const Simulation& simulation) {
  Inputs in;
  const StsCrane& crane = simulation.crane();
  if (done()) {  // clear the truck: raise the empty spreader to travel height
    in.sts.hoist = crane.spreader_pose().position.z < kTravelHeight_m ? 1.0 : 0.0;
    return in;
  }
  const StsCraneSettings& settings = simulation.scenario().crane;
  const double now = simulation.time_s();
  const core::Vec3 spreader = crane.spreader_pose().position;
  const double fall = settings.trolley_rail_height_m - 1.0 - (spreader.z + 0.5);
  const double period = 2.0 * std::numbers::pi * std::sqrt(std::max(fall, 1.0) / 9.80665);
  const core::Vec3 destination = carrying_ ? exercise_.moves[goal_].target_m : source(simulation);
  in.sts.flipper_down = flippers(simulation);
  auto enter = [&](Phase p) {
    phase_ = p;
    phase_start_ = now;
  };

  switch (phase_) {
    case Phase::kRaise:
      in.sts.hoist = 1.0;
      if (spreader.z >= kTravelHeight_m) {
        start_travel(destination, crane.gantry_position_m(), now);
        enter(Phase::kTravel);
      }
      break;
    case Phase::kTravel: {
      in.sts.trolley =
          axis_lever(trolley_, crane.trolley_position_m(), settings.trolley_drive.max_speed_mps, period, now);
      in.sts.gantry =
          axis_lever(gantry_, crane.gantry_position_m(), settings.gantry_drive.max_speed_mps, period, now);
      in.sts.horn = now < gantry_.ramp_start;
      if (in.sts.trolley == 0.0 && in.sts.gantry == 0.0 && !in.sts.horn) enter(Phase::kSettle);
      break;
    }
    case Phase::kSettle: {
      // wait for the swing to slow (in wind the load hangs off plumb, so the offset itself never vanishes),
      // or two periods at most
      const core::Vec3 v = simulation.world().linear_velocity(crane.spreader_body());
      if ((std::hypot(v.x, v.y) < kSettledSwingSpeed_mps && now - phase_start_ > 0.5) ||
          now - phase_start_ > 2 * period)
        enter(Phase::kLower);
      break;
    }
    case Phase::kLower: {
      // landing surface: the spreader's centre when seated on the box (pick-up) or with the box on its target
      const double land_z = destination.z + goal_half_height(simulation) + crane.spreader_half_extents_m().z;
      const bool slow = spreader.z - land_z < kSlowZone_m && !(carrying_ && defects_.land_fast);
      in.sts.hoist = slow ? -kSlowLever : -0.6;
      if (!carrying_ && crane.lamps().landed) enter(Phase::kLock);
      if (carrying_ && simulation.world().pose(*crane.locked_container()).position.z <= destination.z + 0.01)
        enter(Phase::kSlacken);
      break;
    }
    case Phase::kLock:
      if (defects_.forget_lock_once && !lock_skipped_) {
        lock_skipped_ = true;  // hoists straight away without locking, then has to come back down
        enter(Phase::kRaise);
        break;
      }
      in.sts.lock = now - phase_start_ < kButton_s;
      if (now - phase_start_ > 2 * kButton_s && crane.locked_container()) {
        carrying_ = true;
        enter(Phase::kRaise);
      }
      break;
    case Phase::kSlacken:
      // lower on until the ropes carry the spreader alone (the unlock interlock refuses a hanging load)
      in.sts.hoist = -kSlowLever;
      if (now - phase_start_ > kSlacken_s &&
          crane.hoisted_load_n() < 1.15 * settings.spreader.mass_kg * 9.80665)
        enter(Phase::kUnlock);
      break;
    case Phase::kUnlock:
      in.sts.unlock = now - phase_start_ < kButton_s;
      if (now - phase_start_ > 2 * kButton_s && !crane.locked_container()) {
        carrying_ = false;
        ++goal_;
        enter(Phase::kRaise);
      }
      break;
  }
  return in;
}

}  // namespace harbour::sim
