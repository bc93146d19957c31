#include "harbour/machines/mhc/HookAutopilot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "harbour/core/Units.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"

namespace harbour::sim {
namespace {

constexpr double kG = core::kStandardGravity;
constexpr double kClearance_m = 3.0;      // the hook over the piece's top, the piece's bottom over the quay
constexpr double kSlingingGap_m = 1.0;    // the hook's bottom over the piece's top while it is slung
constexpr double kPlacing_m = 0.15;       // the piece this near plumb over its target before it goes down
constexpr double kLowerLever = 0.5;       // hoist lever lowering a piece
constexpr double kTouchLever = 0.05;      // ... as it touches down (0.05 m/s at the hook)
constexpr double kEaseGain_per_m = 0.2;   // ... and per metre above its landing in between
constexpr double kTakeUp_s = 4.0;         // hoisting gently while the slings take the piece
constexpr double kRestingShare = 0.5;     // the ropes carrying less of the piece than this: it rests
constexpr double kEaseRate_per_s = 0.25;  // hoist lever travel per second
constexpr double kSettle_s = 1.0;         // the piece resting this long before the slinger takes it off
constexpr double kSettleAfterUnsling_s = 5.0;  // the empty hook let calm before it is set down after a fault

}  // namespace

std::string HookAutopilot::why_cannot_drive(const ExerciseSettings& exercise) {
  const auto* mhc = exercise.scenario.machine.get_if<MhcSetup>();
  if (!mhc || !mhc->start.on_hook) return "the hook autopilot drives the mobile harbour crane on its hook";
  if (exercise.moves.empty()) return "the exercise has no moves (exercise.moves)";
  return "";
}

HookAutopilot::HookAutopilot(const ExerciseSettings& exercise) : exercise_(exercise) {
  if (const std::string why = why_cannot_drive(exercise); !why.empty()) throw std::invalid_argument(why);
}

const char* HookAutopilot::activity() const {
  switch (phase_) {
    case Phase::kToPiece:
      return "to piece";
    case Phase::kLower:
      return "lower";
    case Phase::kSling:
      return "sling";
    case Phase::kLift:
      return "lift";
    case Phase::kToTarget:
      return "to target";
    case Phase::kSetDown:
      return "set down";
    case Phase::kUnsling:
      return "unsling";
    case Phase::kFaultStop:
      return "fault stop";
    case Phase::kDone:
      return "done";
  }
  return "";
}

void HookAutopilot::resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) {
  move_ = static_cast<std::size_t>(std::max(moves_done, 0));
  phase_ = move_ >= exercise_.moves.size()    ? Phase::kDone
           : simulation.machine().held_item() ? Phase::kLift
                                              : Phase::kToPiece;
  phase_start_s_ = simulation.time_s();
  take_levers(levers);  // its filters start again from what it sees
}

std::size_t HookAutopilot::piece_index(const Simulation& simulation) const {
  const std::vector<ContainerPlacement>& items = simulation.scenario().containers;
  for (std::size_t n = 0; n < items.size(); ++n)
    if (items[n].id == exercise_.moves[move_].container_id) return n;
  throw std::logic_error("the move's piece is not in the scenario");
}

scene::Controls HookAutopilot::decide(const Simulation& simulation, const MobileHarbourCrane& crane) {
  const double now = simulation.time_s();
  const double decision_s = kDecisionSteps * Simulation::kStep_s;
  steering_.observe(crane, decision_s, first_decision());
  double slew = 0.0, luff = 0.0, hoist = 0.0;
  bool call_slinger = false;
  const auto enter = [&](Phase p) {
    phase_ = p;
    phase_start_s_ = now;
  };
  if (phase_ == Phase::kDone) {
    return hand_levers(simulation.control_table(), last_decision(), decision_before_last(), decision_s, {});
  }
  if (phase_ == Phase::kFaultStop) {
    // the hook rid of its piece bounces on its ropes: it is let calm before it goes down
    if (now - phase_start_s_ < kSettleAfterUnsling_s)
      return hand_levers(simulation.control_table(), last_decision(), decision_before_last(), decision_s,
                         {{"hoist", 0.0}});
    return stop_after_hoist_fault(simulation.control_table(), crane, last_decision(), decision_before_last(),
                                  decision_s, crane.settings().hook->block_mass_kg, rest_on_z_m_);
  }
  const std::size_t piece = piece_index(simulation);
  const ContainerPlacement& placed = simulation.scenario().containers[piece];
  const core::Pose pose = simulation.world().pose(simulation.container_body(piece));
  const double half_height = placed.half_extents_m.z;
  const double top = pose.position.z + half_height, bottom = pose.position.z - half_height;
  const MoveGoal& goal = exercise_.moves[move_];
  const double landing = goal.target_m.z - half_height;  // the piece's bottom when it is set down
  // a slung piece's bottom is held by holding the hook's: it hangs a fixed drop below it
  const double hook_over_piece = crane.attachment_bottom_z_m() - bottom;
  const auto hold_piece_bottom = [&](double z) { return steering_.hold_height(z + hook_over_piece); };
  const double slung_kg = simulation.world().mass_kg(simulation.container_body(piece));
  const bool resting =
      crane.limiter_load_n() < (crane.settings().hook->block_mass_kg + kRestingShare * slung_kg) * kG;
  const bool held = crane.held_item().has_value();
  // the hoist brake has failed: nothing more is lifted (a slung piece goes on down to its target); the empty
  // hook comes to rest on the piece under it, or on the quay on its way to one
  const bool fault = crane.fault_active(MachineFault::kHoistBrake);
  const core::Vec3 hook = crane.load_position_m();
  const bool over_piece = std::hypot(hook.x - pose.position.x, hook.y - pose.position.y) <
                          std::max(placed.half_extents_m.x, placed.half_extents_m.y);
  rest_on_z_m_ = over_piece || phase_ != Phase::kToPiece ? top : 0.0;
  if (fault && !held && (phase_ == Phase::kToPiece || phase_ == Phase::kLower || phase_ == Phase::kSling)) {
    enter(Phase::kFaultStop);
    return stop_after_hoist_fault(simulation.control_table(), crane, last_decision(), decision_before_last(),
                                  decision_s, crane.settings().hook->block_mass_kg, rest_on_z_m_);
  }
  const int hoist_slot = simulation.control_table().find("hoist");
  const double last_hoist = last_decision().value[static_cast<std::size_t>(hoist_slot)];

  switch (phase_) {
    case Phase::kToPiece: {
      hoist = steering_.hold_height(top + kClearance_m);
      const bool over = steering_.steer(crane, BoomSteering::target_of(crane, pose.position),
                                        0.2 * crane.settings().hook->slinger_reach_m, slew, luff);
      if (over && steering_.bottom_m() > top + kClearance_m - 1.0) enter(Phase::kLower);
      break;
    }
    case Phase::kLower: {
      const bool over = steering_.steer(crane, BoomSteering::target_of(crane, pose.position),
                                        0.2 * crane.settings().hook->slinger_reach_m, slew, luff);
      const double gap = steering_.bottom_m() - (top + kSlingingGap_m);
      hoist = gap > 2.0 ? -0.5 : steering_.hold_height(top + kSlingingGap_m);
      if (over && std::abs(gap) < 0.4) enter(Phase::kSling);
      break;
    }
    case Phase::kSling:
      steering_.steer(crane, BoomSteering::target_of(crane, pose.position), 1.0, slew, luff);
      call_slinger = !held && now - phase_start_s_ < decision_s;  // one press
      if (held) enter(Phase::kLift);
      if (!held && now - phase_start_s_ > 1.0) enter(Phase::kLower);  // refused: close in again
      break;
    case Phase::kLift:
      hoist = now - phase_start_s_ < kTakeUp_s ? 0.2 : hold_piece_bottom(landing + kClearance_m);
      if (bottom > landing + kClearance_m - 0.5) enter(Phase::kToTarget);
      break;
    case Phase::kToTarget:
      hoist = hold_piece_bottom(std::max(landing, 0.0) + kClearance_m);
      if (steering_.steer(crane, BoomSteering::target_of(crane, goal.target_m), kPlacing_m, slew, luff))
        enter(Phase::kSetDown);
      break;
    case Phase::kSetDown:
      // over the target (within half its tolerance) and calm the boom stands still: a luffing boom's
      // corrections, at the rhythm of the piece's bounce, would pump it
      if (steering_.steer(crane, BoomSteering::target_of(crane, goal.target_m), 0.5 * goal.tolerance_m, slew,
                          luff))
        slew = luff = 0.0;
      // slower the nearer it is
      hoist = resting ? 0.0 : -std::min(kLowerLever, kTouchLever + kEaseGain_per_m * (bottom - landing));
      if (!resting) resting_since_s_ = now;
      if (now - resting_since_s_ > kSettle_s) enter(Phase::kUnsling);
      break;
    case Phase::kUnsling:
      call_slinger = held && now - phase_start_s_ < decision_s;
      if (!held) {
        ++move_;
        enter(fault ? Phase::kFaultStop : move_ < exercise_.moves.size() ? Phase::kToPiece : Phase::kDone);
      } else if (now - phase_start_s_ > 1.0) {
        enter(Phase::kSetDown);  // refused: not resting yet
      }
      break;
    case Phase::kFaultStop:
    case Phase::kDone:
      break;
  }
  // the hoist lever eased: a heavy piece bounces on its long ropes (~1.4 Hz, lightly damped), and a lever
  // moved within a period of that sets it bouncing
  hoist =
      std::clamp(hoist, last_hoist - kEaseRate_per_s * decision_s, last_hoist + kEaseRate_per_s * decision_s);
  scene::Controls out = hand_levers(simulation.control_table(), last_decision(), decision_before_last(),
                                    decision_s, {{"slew", slew}, {"luff", luff}, {"hoist", hoist}});
  if (const int sling = simulation.control_table().find("sling"); sling >= 0)
    out.value[static_cast<std::size_t>(sling)] = call_slinger ? 1.0 : 0.0;
  return out;
}

}  // namespace harbour::sim
