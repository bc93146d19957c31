#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/machines/mhc/BoomSteering.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/sim/DecidingPilot.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {

/// Deliberate faults for a scripted bad grab operator (tests of the evaluation).
struct GrabOperatorDefects {
  bool open_over_the_quay_edge = false;   ///< opens the loaded grab on its way, over the gap to the ship
  bool travel_below_the_coaming = false;  ///< slews back into the hold with the grab below the coaming top
};

/// A scripted grab operator for a bulk delivery exercise on a slewing, luffing crane: hoists clear of the
/// hatch coaming, slews and luffs over the next dig spot in the open hold while it opens the grab, lowers
/// (fast, then slowly near the material), shuts the grab on the material, hoists clear, slews and luffs over
/// the hopper and opens the grab there once the swing is small, and again until the exercise's tonnes are
/// delivered. The boom head follows the grab's swing (a speed proportional to the grab's offset from plumb
/// under it damps the pendulum) while it creeps onto its target. Dig spots: a 3 x 3 pattern over the open
/// hold's hatch, inside the coamings by the grab's half size and a margin; it digs where the material stands
/// highest. Trimming a pile on the quay it digs where the pile stands highest and drops the bite where it
/// lies lowest, away from there, until the pile's top is down to the goal. When the hoist brake fault lamp
/// lights it follows the procedure: a loaded grab is discharged under power where it was going (a grab still
/// on the material opens there), no bite is taken again, the empty grab is set down (beside the hopper, which
/// drains, or on the material under it) and the crane is stopped with the emergency stop.
class GrabAutopilot final : public DecidingPilot<MobileHarbourCrane> {
 public:
  /// Why it cannot drive `exercise` ("" when it can): a delivery goal on the MHC with a bulk carrier's open
  /// hold, or a trim goal.
  static std::string why_cannot_drive(const ExerciseSettings& exercise);
  /// Throws std::invalid_argument with why_cannot_drive() when it cannot.
  explicit GrabAutopilot(const ExerciseSettings& exercise, GrabOperatorDefects defects = {});

  /// What it is doing now: to dig, lower, shut, hoist, to drop (the hopper, the pile's low spot), discharge,
  /// fault stop, done.
  const char* activity() const override;
  /// Takes over a running exercise: hoists a loaded grab out to the hopper, or goes to dig with an empty one.
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override;
  int bites() const { return bites_; }

 private:
  enum class Phase { kToDig, kLower, kShut, kHoist, kToDrop, kDischarge, kOpenAfterFault, kFaultStop, kDone };
  scene::Controls decide(const Simulation& simulation, const MobileHarbourCrane& crane) override;
  bool drives(const Simulation& simulation, const MobileHarbourCrane&) const override {
    return simulation.bulk() && simulation.bulk_grab() >= 0;
  }
  core::Vec3 dig_spot(const Simulation& simulation) const;
  void choose_dig_spot(const Simulation& simulation);
  /// Trimming a pile: the dig and drop spots and the travel height from the pile as it stands now.
  void choose_trim_spots(const Simulation& simulation, const MobileHarbourCrane& crane);

  ExerciseSettings exercise_;
  GrabOperatorDefects defects_;
  Phase phase_ = Phase::kToDig;
  int bites_ = 0;
  double phase_start_s_ = 0.0;
  std::optional<VesselGeometry> vessel_;  // the scenario's bulk carrier, built once
  std::vector<core::Vec3> spots_;         // vessel frame
  std::size_t spot_ = 0;                  // the one it digs next
  BoomSteering steering_;
  core::Vec3 pile_dig_m_, dump_m_;  // trimming: where it digs and drops (world)
  double travel_z_m_ = 0.0;         // trimming: the grab's bottom height while it travels
  core::Vec3 rest_spot_m_;          // after a hoist brake fault: where the empty grab is set down
  bool reached_rest_spot_ = false;  // ... over it
};

}  // namespace harbour::sim
