#pragma once

#include <algorithm>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "harbour/cable/HoistSystem.h"
#include "harbour/core/Units.h"
#include "harbour/machines/parts/LimitSwitches.h"
#include "harbour/machines/parts/OdeCableBodies.h"
#include "harbour/machines/parts/Spreader.h"
#include "harbour/machines/parts/SpreaderLocks.h"
#include "harbour/sim/Machine.h"

namespace harbour::sim {

/// A container spreader hanging from a trolley on a cable reeving (settings): the STS's and the RTG's.
struct SpreaderHoistSettings {
  SpreaderSettings spreader;
  TwistlockSettings twistlocks;
  cable::ReevingSettings
      hoist;                    ///< its last body is the headblock (the spreader), the one before the trolley
  double upper_limit_m = 44.0;  ///< [m] spreader centre height where the upper limit switch stops hoisting
  double lower_limit_m = -20.0;  ///< [m] ... and the lower one stops lowering
};

/// What the operator asks of the hoist and the spreader in one step.
struct SpreaderHoistCommand {
  double hoist = 0.0;  ///< [-1, 1] +: raise
  bool lock = false, unlock = false, emergency_stop = false;
  std::uint8_t spreader_size_ft = 0;   ///< a size button held: 20, 40 or 45 (0: none)
  std::array<bool, 4> flipper_down{};  ///< flipper switches per corner (true: lowered)
};

/// The spreader on its hoist ropes: the winch with its limit switches, the telescoping frame and flippers,
/// and the twistlocks that lock a landed container to it. Its faults: a hoist brake that does not set and a
/// corner's landed sensor reading "not landed".
class SpreaderHoist {
 public:
  /// `bodies`: the reeving's bodies but the last (the trolley among them); the headblock is the
  /// spreader's body, built here at `spreader_pose` (its length along its y).
  SpreaderHoist(physics::PhysicsWorld& world, const SpreaderHoistSettings& settings,
                std::vector<physics::BodyId> bodies, const core::Pose& spreader_pose);

  void step(const SpreaderHoistCommand& command, std::span<const ContainerRef> containers, double dt_s);

  physics::BodyId spreader_body() const { return spreader_; }
  double spreader_mass_kg() const { return settings_.spreader.mass_kg; }
  /// The payload a cab's load display shows [t]: the falls' pull on the headblock (their tension less the
  /// half of their own weight that the headblock does not carry) less the spreader's weight (tared), not
  /// below zero.
  double net_load_t() const;
  double upper_limit_m() const { return settings_.upper_limit_m; }
  const Spreader& spreader() const { return *frame_; }
  SpreaderState spreader_state() const { return frame_->state(); }
  const SpreaderLocks& locks() const { return locks_; }
  SpreaderLocks& locks() { return locks_; }
  std::optional<physics::BodyId> locked_container() const { return locks_.locked_container(); }
  const cable::HoistSystem& hoist() const { return *hoist_; }
  cable::HoistSystem& hoist() { return *hoist_; }
  /// Vertical rope pull on the headblock [N] (the load the hoist carries, spreader included).
  double hoisted_load_n() const;
  /// The falls' length: from their upper ends (the trolley's sheaves, a drum or dead end the rope comes
  /// down from) to the headblock's sheaves, mean heights [m].
  double pendulum_length_m() const;
  double attachment_bottom_z_m() const;
  /// The spreader's speed at full lever [m/s] (the drum's rope speed over the falls per rope).
  double full_hoist_speed_mps() const;
  /// The speed the drum hoists the spreader at now [m/s], positive up (its rope speed over the falls per
  /// rope).
  double hoisting_speed_mps() const { return -hoist_->drum_rope_speed(0) / falls_per_rope_; }
  double lowering_speed_mps() const { return -hoisting_speed_mps(); }
  /// Stretches the ropes under the hanging spreader's weight, shared by the falls (before the first step).
  void settle_ropes() {
    hoist_->pretension(settings_.spreader.mass_kg * core::kStandardGravity /
                       static_cast<double>(falls_.size()));
  }
  /// The falls the headblock hangs on.
  int fall_count() const { return static_cast<int>(falls_.size()); }
  /// The falls' own weight [N] (their length times the rope's mass per metre).
  double falls_weight_n() const;
  std::uint32_t limit_hits() const { return limits_.hits(); }
  bool at_limit() const { return limits_.at_limit(); }

  void inject_brake_fault() { brake_fault_ = true; }
  bool brake_fault() const { return brake_fault_; }
  bool landed_sensor_fault() const { return landed_sensor_fault_ >= 0; }
  void inject_landed_sensor_fault(int corner) { landed_sensor_fault_ = corner; }
  void clear_faults();

  /// The frame, twistlocks, ropes, joint, faults and limit switches, in that order.
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar.part(*self.frame_);
    ar.part(self.locks_.twistlocks());
    ar.part(*self.hoist_);
    ar.part(self.locks_);
    ar(self.brake_fault_);
    ar.part(self.limits_);
    ar(self.landed_sensor_fault_);
  }
  physics::PhysicsWorld& world_;
  SpreaderHoistSettings settings_;
  physics::BodyId spreader_;
  core::Vec3 headblock_sheaves_m_;          // their mean position, the headblock's frame
  std::vector<std::pair<int, int>> falls_;  // (rope, segment) of the ropes' falls to the headblock
  std::vector<cable::Mount> fall_tops_;     // the falls' upper ends
  double falls_per_rope_ = 1.0;
  std::unique_ptr<Spreader> frame_;
  SpreaderLocks locks_;
  std::unique_ptr<OdeCableBodies> cable_bodies_;
  std::unique_ptr<cable::HoistSystem> hoist_;
  LimitSwitches limits_;
  bool brake_fault_ = false;
  int landed_sensor_fault_ = -1;
};

}  // namespace harbour::sim
