#pragma once

#include <string>
#include <vector>

#include "harbour/machines/reach_stacker/ReachStacker.h"
#include "harbour/sim/DecidingPilot.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {

/// The stacks on a reach stacker's line between where it carries a box from and its target.
struct StacksInTheWay {
  double nearest_face_along_m;  // the face of the nearest one it stops short of (the target's own if none)
  double highest_top_m;         // the top it raises the box over (0: none)
};

/// A scripted reach stacker driver for one box's move along its lane: drives up to the box ahead, brings
/// the spreader over it, lands, locks and lifts it, carries it low towards its target further along the
/// lane, stops short of the stacks in front of the target to raise it over them, creeps on to where the
/// target lies within reach, reaches out over it, sets it down, unlocks, and lifts the spreader clear. The
/// boom's head is steered along straight lines (the lift and extension levers from the head's wanted velocity
/// through the boom's geometry); the side-shift and rotation square the spreader on the box.
class ReachStackerAutopilot final : public DecidingPilot<ReachStacker> {
 public:
  /// Why it cannot drive `exercise` ("" when it can): a reach stacker with one move whose box lies ahead of
  /// it on its line and whose target lies further along that line.
  static std::string why_cannot_drive(const ExerciseSettings& exercise);
  /// Throws std::invalid_argument with why_cannot_drive() when it cannot.
  explicit ReachStackerAutopilot(const ExerciseSettings& exercise, DriverDefects defects = {});

  /// What it is doing now: approach, pick, lock, lift, carry, raise, creep, reach, set, unlock, clear, done.
  const char* activity() const override;
  /// Takes over a running exercise from where the machine stands and what it holds.
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override;

 private:
  enum class Phase {
    kApproach,
    kPick,
    kLock,
    kLift,
    kCarry,
    kRaise,
    kCreep,
    kReach,
    kSet,
    kUnlock,
    kClear,
    kDone
  };
  scene::Controls decide(const Simulation& simulation, const ReachStacker& machine) override;
  StacksInTheWay stacks_before_target(const Simulation& simulation) const;
  /// Carries the box from `where_m` along the exercise's route, then along the line to the target.
  void take_route_from(const core::Vec3& where_m);
  /// No truck stands in or near its lane's stop (the one it took the box from has driven off).
  bool way_clear(const Simulation& simulation) const;

  ExerciseSettings exercise_;
  DriverDefects defects_;
  Phase phase_ = Phase::kApproach;
  double phase_start_s_ = 0.0;
  core::Vec3 lane_start_m_, lane_along_;  // the lane's line: from where it started, along its heading; on a
                                          // route, from its last point to the target once it carries
  std::vector<core::Vec3> carry_path_;    // the route from where it picked the box (empty: none)
  std::size_t box_index_ = 0;             // the moved box among the scenario's containers
};

}  // namespace harbour::sim
