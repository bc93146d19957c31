#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "harbour/machines/GantryCrane.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour::sim {

/// Deliberate faults for a scripted bad operator (tests of the evaluation).
struct OperatorDefects {
  bool land_fast = false;         ///< set containers down at full lowering speed
  bool forget_lock_once = false;  ///< hoist away from the first pick-up without locking, then come back
  bool never_steer = false;       ///< a gantry on tyres: leave the steering alone, whatever its bias
  bool skip_horn = false;         ///< travel the gantry without sounding the horn first
  bool stop_at_fault = false;     ///< press the emergency stop as the hoist brake fault lamp lights
};

/// A scripted operator that performs an exercise's moves: sway-aware travel (levers ramped up and down over
/// one pendulum period of the current rope length, which leaves almost no residual swing), then fine
/// positioning as a skilled driver does it: the trolley and gantry follow the swing to catch it (a speed
/// proportional to the load's offset from where it hangs at rest damps the pendulum) while they creep the
/// load's rest position onto the target; fast-then-slow lowering that holds just above the landing until the
/// load is on target and calm, lifting off to try again when the spreader sits beside the castings; locking,
/// unlocking. For headless runs, demos, tests.
class GantryAutopilot final : public Pilot {
 public:
  /// Why it cannot drive `exercise` ("" when it can): it drives the container moves of a gantry crane (the
  /// STS, an RTG square to the world).
  static std::string why_cannot_drive(const ExerciseSettings& exercise);
  /// Throws std::invalid_argument with why_cannot_drive() when it cannot.
  explicit GantryAutopilot(const ExerciseSettings& exercise, OperatorDefects defects = {});

  /// The controls for the next step, from what the simulation shows now (decided 50 times a second, held
  /// in between, levers at a joystick axis' 16-bit resolution).
  scene::Controls next(const Simulation& simulation) override;
  bool done() const { return goal_ >= exercise_.moves.size(); }
  /// What it is doing now, for progress displays: raise, travel, settle, lower, lift off, lock, slacken,
  /// unlock.
  const char* activity() const override;
  /// Takes over a running exercise (an instructor's take-over): the first `moves_done` moves are made; if the
  /// spreader holds the next move's box it carries it on, else it goes to fetch it (raising first, then
  /// catching whatever swing the load has before it lowers). Its hands start from `levers`, the levers as
  /// they stood, and move them as a hand does until they reach its own.
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override;

 private:
  enum class Phase { kRaise, kTravel, kSettle, kLower, kLiftOff, kLock, kSlacken, kUnlock };
  struct AxisMove {
    double target = 0.0;
    double peak = 0.0;        // lever magnitude reached
    double ramp_start = 0.0;  // [s]
    bool decelerating = false;
    double decel_from = 0.0;  // lever when braking began
    double top = -1.0;        // lever to ramp to (set on the first step: short moves never reach cruise)
  };

  /// Fine positioning of one axis (see the class comment).
  struct SwingAxis {
    double rest_offset = 0.0;  // [m] where the load hangs at rest relative to the axis, wind aside (filtered)
    bool primed = false;
    double swing = 0.0;  // [m] estimated swing amplitude about the rest offset
    double error = 0.0;  // [m] target minus the load's rest position
    double miss = 0.0;   // [m] the load's distance from the target, now or half a second on
    double last_target = 0.0;
  };
  static const GantryCrane& crane(const Simulation& simulation);
  GantryLevers decide(const Simulation& simulation);
  /// The steering lever that holds a gantry on tyres on its line.
  double steer(const Simulation& simulation);
  double axis_lever(AxisMove& m, double position, double max_speed, double period, double now) const;
  static double catch_swing(SwingAxis& axis, double target, double axis_position, double axis_speed,
                            double load_position, double load_speed, double wind_lean, double period,
                            double max_speed);
  /// Levers of trolley and gantry that catch the swing and creep the load onto `destination`.
  void position_finely(const Simulation& simulation, const core::Vec3& destination, double period,
                       GantryLevers& in);
  bool on_target(double tolerance) const;  // rest position on target and swing small
  /// The levers a hand sets on the way from the taken-over ones to `wanted` (hand_lever()).
  scene::Controls catch_up(const scene::ControlTable& table, const scene::Controls& wanted);
  bool will_land_within(double tolerance) const;
  /// In a yard: the spreader height at which the load clears the stacks on its way to `destination`.
  double height_over_stacks(const Simulation& simulation, const core::Vec3& destination) const;
  void start_travel(const core::Vec3& to, double gantry_y, double now);
  core::Vec3 source(const Simulation& simulation) const;
  double goal_half_height(const Simulation& simulation) const;
  /// Spreader centre height at which to aim before entering the goal's hold cell (none: not in a cell).
  std::optional<double> cell_entry_z(const Simulation& simulation) const;
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
  SwingAxis trolley_swing_, gantry_swing_;
  double resting_since_ = -1.0;  // the spreader sits on something without landing in its castings
  double stalled_since_ = -1.0;  // lowering: when the spreader last came kProgress_m lower, and where
  double stalled_z_ = 0.0;
  double landed_since_ = -1.0;  // lowering: when the landed lamp lit
  bool lock_skipped_ = false;
  double lane_integral_ = 0.0;  // [m s] the gantry's offset from its line, integrated while it travels
  GantryLevers last_;
  scene::Controls last_controls_;
  bool decided_ = false;
  bool catching_up_ = false;            // after a take-over: the hands still move to this operator's levers
  scene::Controls hand_, hand_before_;  // the levers the hands set at the last two decisions
};

}  // namespace harbour::sim
