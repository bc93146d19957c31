#pragma once

#include <string>
#include <vector>

#include "harbour/machines/tractor/TerminalTractor.h"
#include "harbour/sim/DecidingPilot.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {

/// A scripted tractor driver for a trailer's parking move: drives on from where it stands to the line the
/// trailer is to stand on (through the corner where its heading's line meets that line), steering by pure
/// pursuit of a point ahead on that path from its rear axle, brings the trailer straight on the final line,
/// eases to a stop with the trailer's centre on its target, and drops it. A target behind the trailer it
/// reverses into: the trailer's axles follow a path onto the bay's line (pure pursuit of a point behind
/// them gives the trailer's curvature, hence the hitch angle that turns it so), and the tractor's steering
/// holds that hitch angle (reversing, the hitch angle runs away by itself; the steering leads it back). With
/// a load stop it first drives so onto the stop, waits there until a team's crane has set its box on the
/// trailer, then drives on to its move's target.
class TractorAutopilot final : public DecidingPilot<TerminalTractor> {
 public:
  /// Why it cannot drive `exercise` ("" when it can): a move of the tractor's trailer.
  static std::string why_cannot_drive(const ExerciseSettings& exercise);
  /// Throws std::invalid_argument with why_cannot_drive() when it cannot.
  explicit TractorAutopilot(const ExerciseSettings& exercise, DriverDefects defects = {});

  /// What it is doing now: drive, stop, drop, done.
  const char* activity() const override;
  /// Takes over a running exercise: plans its path again from where the tractor stands.
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override;

 private:
  enum class Phase { kDrive, kStop, kWaitForLoad, kDrop, kDone };
  /// Where it is driving to now: the load stop (an exercise's team pick-up, until the box is on) or its
  /// move's target.
  struct Leg {
    core::Vec3 target_m;
    double heading_rad = 0.0;
  };
  Leg leg() const;
  scene::Controls decide(const Simulation& simulation, const TerminalTractor& tractor) override;
  void plan(const Simulation& simulation, const TerminalTractor& tractor);
  /// How far the trailer's centre still is from its target along the goal's heading [m].
  double remaining_m(const Simulation& simulation, const TerminalTractor& tractor) const;

  /// Reversing: the steering that turns the trailer's axles onto the path behind them.
  double reversing_steer(const Simulation& simulation, const TerminalTractor& tractor) const;
  /// The trailer's axles' centre along its x [m] (its frame).
  double trailer_axles_x_m() const;

  ExerciseSettings exercise_;
  DriverDefects defects_;
  bool reversing_ = false;     // the target lies behind the trailer
  bool to_load_stop_ = false;  // on the way to the load stop, or waiting there
  Phase phase_ = Phase::kDrive;
  std::vector<core::Vec3> path_;  // the polyline its rear axle follows (ground plane)
  bool planned_ = false;
  double phase_start_s_ = 0.0;
  double speed_integral_ = 0.0;  // its throttle's integral part
};

}  // namespace harbour::sim
