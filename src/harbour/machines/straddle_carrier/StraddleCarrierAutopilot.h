#pragma once

#include <string>
#include <vector>

#include "harbour/machines/straddle_carrier/StraddleCarrier.h"
#include "harbour/sim/DecidingPilot.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {

/// A scripted straddle carrier driver for one box's move: drives along the row it straddles with the
/// spreader over every stack on the way, stops with the spreader over the box, lowers it onto the box, locks,
/// lifts the box clear of the stacks, drives on (along the row, or the exercise's route) to the target, sets
/// the box down, unlocks and lifts the spreader clear. It steers by pure pursuit on its way and stops by the
/// distance left along it (creeping the last metre, the swing caught by inching before it lands).
class StraddleCarrierAutopilot final : public DecidingPilot<StraddleCarrier> {
 public:
  /// Why it cannot drive `exercise` ("" when it can): a straddle carrier with one move whose box lies on its
  /// line ahead of it, and whose target lies further along that line or at the end of the exercise's route.
  static std::string why_cannot_drive(const ExerciseSettings& exercise);
  /// Throws std::invalid_argument with why_cannot_drive() when it cannot.
  explicit StraddleCarrierAutopilot(const ExerciseSettings& exercise);

  /// What it is doing now: approach, land, lock, lift, carry, set, unlock, clear, done.
  const char* activity() const override;
  /// Takes over a running exercise from where the machine stands and what it holds.
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override;

 private:
  enum class Phase { kApproach, kLand, kLock, kLift, kCarry, kSet, kUnlock, kClear, kDone };
  scene::Controls decide(const Simulation& simulation, const StraddleCarrier& machine) override;

  ExerciseSettings exercise_;
  Phase phase_ = Phase::kApproach;
  double phase_start_s_ = 0.0;
  std::vector<core::Vec3> path_;  // its way: along the row from where it started, the route, to the target
  std::size_t box_index_ = 0;     // the moved box among the scenario's containers
};

}  // namespace harbour::sim
