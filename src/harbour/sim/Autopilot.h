#pragma once

#include <array>
#include <cstdint>

#include "harbour/sim/Evaluation.h"

namespace harbour::sim {

/// Deliberate faults for a scripted bad operator (tests of the evaluation).
struct OperatorDefects {
  bool land_fast = false;         ///< set containers down at full lowering speed
  bool forget_lock_once = false;  ///< hoist away from the first pick-up without locking, then come back
};

/// A scripted operator that performs an exercise's moves: sway-aware travel (levers ramped up and down over
/// one pendulum period of the current rope length, which leaves no residual swing), then a creep onto the
/// target and a wait for the swing to die, fast-then-slow lowering, locking, unlocking. For headless runs,
/// demos, tests.
class Autopilot {
 public:
  explicit Autopilot(const ExerciseSettings& exercise, OperatorDefects defects = {});

  /// The controls for the next step, from what the simulation shows now.
  Inputs next(const Simulation& simulation);
  bool done() const { return goal_ >= exercise_.moves.size(); }
  /// Takes over a running exercise (an instructor's take-over): the first `moves_done` moves are made; if the
  /// spreader holds the next move's box it carries it on, else it goes to fetch it. It cannot catch a big
  /// swing: take over where the load hangs calm (at a pick-up, a set-down, before travelling).
  void resume(const Simulation& simulation, int moves_done);

 private:
  enum class Phase { kRaise, kTravel, kSettle, kLower, kLock, kSlacken, kUnlock };
  struct AxisMove {
    double target = 0.0;
    double peak = 0.0;        // lever magnitude reached
    double ramp_start = 0.0;  // [s]
    bool decelerating = false;
    double decel_from = 0.0;  // lever when braking began
    double top = -1.0;        // lever to ramp to (set on the first step: short moves never reach cruise)
  };

  double axis_lever(AxisMove& m, double position, double max_speed, double period, double now) const;
  void start_travel(const core::Vec3& to, double gantry_y, double now);
  core::Vec3 source(const Simulation& simulation) const;
  double goal_half_height(const Simulation& simulation) const;
  std::size_t goal_index(const Simulation& simulation) const;  // the goal item in the scenario
  /// Flipper switches for the goal: down for a box standing free, else up.
  std::array<bool, 4> flippers(const Simulation& simulation) const;

  ExerciseSettings exercise_;
  OperatorDefects defects_;
  std::size_t goal_ = 0;
  bool carrying_ = false;
  Phase phase_ = Phase::kRaise;
  double phase_start_ = 0.0;
  AxisMove trolley_, gantry_;
  bool lock_skipped_ = false;
};

}  // namespace harbour::sim
