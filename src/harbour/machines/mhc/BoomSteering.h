#pragma once

#include <initializer_list>
#include <utility>

#include "harbour/core/Vec3.h"
#include "harbour/scene/Controls.h"

namespace harbour::sim {

class MobileHarbourCrane;

/// How a scripted operator drives a slewing, luffing crane's boom head: over a point while it damps the
/// load's swing (the head follows the load's offset from plumb under the falls), and the load at a height
/// held gently. It sees the swing and the height through a low-pass: the boom's bounce on its ropes (about 1
/// Hz) moves the head to and fro under the load, and levers that followed it would pump the bounce; a
/// slower one lags the load's pendulum enough to pump its swing.
class BoomSteering {
 public:
  /// Where a point lies from the slewing axis.
  struct Target {
    double slew_rad = 0.0, radius_m = 0.0;
  };
  static Target target_of(const MobileHarbourCrane& crane, const core::Vec3& point);

  /// Takes in what the crane shows now, once a decision (every `decision_s`); `restart`: the filters start
  /// again from it (the first decision, a take-over).
  void observe(const MobileHarbourCrane& crane, double decision_s, bool restart);
  /// Slew and luff levers that bring the boom head over `target` while they damp the load's swing; true when
  /// the load is within `tolerance_m` of plumb over it and calm.
  bool steer(const MobileHarbourCrane& crane, const Target& target, double tolerance_m, double& slew,
             double& luff) const;
  /// The hoist lever that holds the attachment's bottom at `z_m` (a low gain beyond a dead band, no step at
  /// its edge: the load bounces on its ropes if the hoist hunts).
  double hold_height(double z_m) const;
  /// The attachment's bottom height as it sees it [m] (low-passed).
  double bottom_m() const { return held_bottom_m_; }

 private:
  core::Vec3 swing_m_;                // the load's offset from plumb under the falls, low-passed
  double slew_reference_ = 0.0;       // the slewing drive's ramped reference at the last decision [rad/s]
  int slew_speeding_ = 0;             // the way its magnitude last changed (+1 up, -1 down)
  double slew_speeding_ago_s_ = 1e9;  // since it last changed [s]
  double held_bottom_m_ = 0.0;
};

/// The hoist brake fault's procedure, its last step, once the load is down under power: the empty attachment
/// (`empty_kg`) is lowered onto what lies below it (its top at about `rest_on_z_m`), slower the nearer it is,
/// until it rests (its ropes carrying less than half its weight), the boom moved by `slew` and `luff` (those
/// that keep it calm over its spot); then the emergency stop is pressed so that nothing runs the unbraked
/// hoist again.
scene::Controls stop_after_hoist_fault(const scene::ControlTable& table, const MobileHarbourCrane& crane,
                                       const scene::Controls& last, const scene::Controls& before_last,
                                       double decision_s, double empty_kg, double rest_on_z_m,
                                       double slew = 0.0, double luff = 0.0);

/// Levers moved as a hand moves them: each labelled lever goes towards its wanted value by at most
/// `decision_s / lever_travel_s` of full travel from where it was (`last`), and its speed changes gradually
/// from how it moved in the decision before (`last` against `before_last`); the others stay neutral.
scene::Controls hand_levers(const scene::ControlTable& table, const scene::Controls& last,
                            const scene::Controls& before_last, double decision_s,
                            std::initializer_list<std::pair<const char*, double>> wanted);
/// One lever of hand_levers(): where it stands after a decision that wants it at `wanted`.
double hand_lever(double last, double before_last, double wanted, double decision_s);

}  // namespace harbour::sim
