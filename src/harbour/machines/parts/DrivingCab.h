#pragma once

#include <vector>

#include "harbour/core/StateArchive.h"
#include "harbour/machines/parts/WheeledChassis.h"
#include "harbour/scene/Controls.h"

namespace harbour::sim {

/// A vehicle's driving controls at work: hydraulic steering that follows the wheel at its rate, the drive cut
/// in neutral, the parking brake's switch passed on to the chassis, the emergency stop cutting the drive and
/// braking fully. Shared by the driven machines.
class DrivingCab {
 public:
  /// `table` has the driving controls every driven vehicle's cab has (its machine file declares them, checked
  /// by io::require_driving_controls): steer, throttle, brake, direction, parking_brake, emergency_stop and
  /// horn (throws std::invalid_argument naming one it lacks).
  DrivingCab(const scene::ControlTable& table, double steer_rate_per_s);

  /// The chassis's command for one step of `dt_s` from controls already in range.
  ChassisCommand step(const scene::Controls& controls, double dt_s);
  /// The steering as it stands now [-1, 1].
  double steering() const { return steering_; }
  bool horn() const { return horn_; }
  bool emergency_stop() const { return stop_; }
  /// The direction selector as last read: -1 reverse, 0 neutral, 1 forward (for the cab's display).
  int direction() const { return direction_; }
  /// The parking brake's switch as last read (set: true).
  bool parking_brake() const { return parking_; }
  void save_state(core::StateWriter& out) const { archive(*this, out); }
  void restore_state(core::StateReader& in) { archive(*this, in); }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar(self.steering_, self.horn_);
  }

  int steer_slot_, throttle_slot_, brake_slot_, direction_slot_, parking_slot_, stop_slot_, horn_slot_;
  double steer_rate_per_s_;
  double steering_ = 0.0;
  bool horn_ = false, stop_ = false, parking_ = false;
  int direction_ = 0;
};

}  // namespace harbour::sim
