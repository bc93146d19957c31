#pragma once

#include <string>

#include "harbour/machines/mhc/BoomSteering.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/sim/DecidingPilot.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {

/// A scripted hook operator for general-cargo moves on a slewing, luffing crane: hoists the hook to travel
/// height, brings it over the piece's centre (the head damping the hook's swing), lowers it to just above the
/// piece's top and calls the slinger, lifts the piece gently until its slings take it and then clear of the
/// quay, slews and luffs it over its target, lowers it (slowly for the last metre and a half), calls the
/// slinger to unsling it once it rests, and goes on to the next move. When the hoist brake fault lamp lights
/// it follows the procedure: a slung piece is set down on its target under power and unslung, nothing is
/// lifted again, the empty hook is lowered until it rests and the crane is stopped with the emergency stop.
class HookAutopilot final : public DecidingPilot<MobileHarbourCrane> {
 public:
  /// Why it cannot drive `exercise` ("" when it can): moves for the MHC on its hook.
  static std::string why_cannot_drive(const ExerciseSettings& exercise);
  /// Throws std::invalid_argument with why_cannot_drive() when it cannot.
  explicit HookAutopilot(const ExerciseSettings& exercise);

  /// What it is doing now: to piece, lower, sling, lift, to target, set down, unsling, fault stop, done.
  const char* activity() const override;
  /// Takes over a running exercise: carries a slung piece to its target, or goes to the next piece.
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override;

 private:
  enum class Phase { kToPiece, kLower, kSling, kLift, kToTarget, kSetDown, kUnsling, kFaultStop, kDone };
  scene::Controls decide(const Simulation& simulation, const MobileHarbourCrane& crane) override;
  bool drives(const Simulation&, const MobileHarbourCrane& crane) const override { return crane.on_hook(); }
  /// The scenario's index of the move's piece.
  std::size_t piece_index(const Simulation& simulation) const;

  ExerciseSettings exercise_;
  Phase phase_ = Phase::kToPiece;
  std::size_t move_ = 0;  // the move it is making
  double phase_start_s_ = 0.0;
  double resting_since_s_ = 0.0;  // setting down: since when the piece rests
  double rest_on_z_m_ = 0.0;      // after a hoist brake fault: the top of what the empty hook is set down on
  BoomSteering steering_;
};

}  // namespace harbour::sim
