#pragma once

#include <optional>
#include <span>

#include "harbour/machines/parts/Spreader.h"
#include "harbour/machines/parts/Twistlocks.h"
#include "harbour/sim/Machine.h"

namespace harbour::sim {

/// A spreader's twistlocks at work on its body: the container they are seated in (its top corner castings
/// under the four pins), the locks with their interlocks, and the fixed joint that holds a locked container
/// to the spreader until it is unlocked. Shared by every machine with a container spreader.
class SpreaderLocks {
 public:
  /// One control step: finds the container under the pins (`faulty_corner` 0-3 reads "not landed" whatever
  /// it sits on; -1: none), works the locks (`load_suspended`: the spreader carries clearly more than its
  /// own weight) and makes or breaks the joint.
  void step(physics::PhysicsWorld& world, physics::BodyId spreader, const Spreader& frame,
            std::span<const ContainerRef> containers, const TwistlockSettings& settings, bool lock,
            bool unlock, bool load_suspended, int faulty_corner, double dt_s);

  std::optional<physics::BodyId> locked_container() const { return locked_; }
  const Twistlocks& twistlocks() const { return twistlocks_; }
  Twistlocks& twistlocks() { return twistlocks_; }
  /// The locked container and its joint (the twistlocks save themselves: twistlocks()).
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);

  Twistlocks twistlocks_;
  std::optional<physics::BodyId> locked_;
  physics::AttachmentId attachment_;
};

}  // namespace harbour::sim
