#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "harbour/cable/CableBodies.h"
#include "harbour/cable/Reeving.h"
#include "harbour/core/StateArchive.h"
#include "harbour/core/StateHash.h"

namespace harbour::cable {

/// What the cable model reports (edge-triggered: once when a condition starts).
enum class CableEventKind : std::uint8_t {
  kOverload,       ///< a segment's tension stood 10 ms above the working load limit (MBF / safety factor)
  kBreakingForce,  ///< a segment's tension exceeded the minimum breaking force
  kSlack,          ///< a segment of a rope went slack (zero tension)
};

struct CableEvent {
  CableEventKind kind;
  int rope = 0;
  int segment = 0;
  double tension_n = 0.0;
};

/// Drum commands: normalised lever positions, +1 pays out at full speed (lowers), -1 reels in (hoists).
struct DrumCommand {
  double lever = 0.0;
  bool brake_fault = false;   ///< the holding brake does not engage (fault injection)
  bool motor_enabled = true;  ///< false at an emergency stop: no motor torque, the brake sets at once
};

/// Any block-and-tackle as data (§3.2): drums, sheaves and anchors joined by rope segments. Each segment is
/// an axially moving string whose transverse motion follows the wave equation with transport velocity and
/// end-motion inertia, or a massless spring when that would need too many sub-steps. Sheaves turn under the
/// tension difference of their segments and move unstretched rope between them; drums pay it out or reel it
/// in. Forces reach the bodies through CableBodies.
class HoistSystem {
 public:
  /// Builds the reeving with every segment unstretched at the bodies' current positions.
  HoistSystem(const ReevingSettings& settings, const CableBodies& bodies, const core::Vec3& gravity);

  /// Before the first step: stretches every segment to carry `tension_n` where the bodies are now, the
  /// stretch taken from the rope on the drums (a block-and-tackle at rest carries one tension along each
  /// rope; without it a load starts on unstretched ropes, drops and bounces on them).
  void pretension(double tension_n);
  /// Stops every segment's transverse motion where it is (its shape kept): with the end bodies stopped, the
  /// kinetic damping that settles a machine at rest before it starts. Not on the chord's stretch
  /// (ReevingSettings::stretch_along_chord): the runs recorded on it settled without.
  void stop_transverse_motion();

  /// Advances by `dt_s` (one command per drum, in element order of the drums) and adds the rope forces
  /// to the bodies.
  void step(double dt_s, std::span<const DrumCommand> drum_commands, CableBodies& bodies);

  int rope_count() const { return static_cast<int>(ropes_.size()); }
  int segment_count(int rope) const { return static_cast<int>(ropes_[rope].segments.size()); }
  /// Tension of a segment [N] (axial, uniform along it).
  double tension(int rope, int segment) const { return segment_at(rope, segment).tension; }
  /// The highest tension in any segment of any rope now [N] (what a load cell on the ropes reads).
  double highest_tension_n() const;
  /// True while the segment integrates its transverse oscillation (false: massless spring).
  bool oscillating(int rope, int segment) const { return segment_at(rope, segment).oscillating; }
  /// Unstretched rope in a segment [m].
  double unstretched_length(int rope, int segment) const { return segment_at(rope, segment).rest_length; }
  /// All of a rope's unstretched length, in segments and on its drums [m]: conserved.
  double rope_length(int rope) const;
  /// Transverse displacement of a segment's middle node from its chord [m].
  core::Vec3 midspan_displacement(int rope, int segment) const;
  /// Rope speed at a drum [m/s] (positive pays out) and the torque the rope puts on it [N m].
  double drum_rope_speed(int drum) const;
  double drum_rope_torque(int drum) const;
  /// Power a drum's motor delivers [W] (negative: it brakes a lowering load).
  double drum_power_w(int drum) const;
  /// A drum's settings (its rated rope speed and motor torque).
  const ElementSettings& drum_settings(int drum) const;
  int drum_count() const { return static_cast<int>(drums_.size()); }
  /// Elastic energy of the ropes plus kinetic energy of transverse motion, sheaves and drums [J].
  double energy() const;
  /// Events since the last call.
  std::vector<CableEvent> take_events();
  /// Appends the events since the last call to `into` (no allocation while its capacity lasts).
  void drain_events(std::vector<CableEvent>& into);
  /// Segment `segment` of `rope` as a polyline in the world: its ends and interior nodes (chord plus
  /// transverse displacement), at most out.size() points spread along it; returns how many were written.
  int polyline(int rope, int segment, std::span<core::Vec3> out) const;

  void hash_into(core::StateHash& hash) const;

  /// The dynamic state (rope fields, drums and sheaves) for a keyframe; restore into the same reeving.
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  struct Segment {
    int rope = 0, a = 0, b = 0;   // element indices of its ends (a: towards the drum)
    double rest_length = 0.0;     // [m] unstretched
    double length = 0.0;          // [m] current, along the (curved) rope
    double chord_length = 0.0;    // [m] current, end to end
    double tension = 0.0;         // [N]
    double stiffness = 0.0;       // [N/m] dT / d(rest length)
    double switch_tension = 0.0;  // [N] tension at which it became a spring
    bool oscillating = true;
    double sag_share = 0.0;  // [-] share of the cross-chord weight carried through the sag
    bool slack = false, overloaded = false, breaking = false;
    double over_s = 0.0;                // [s] how long its tension has stood above the working load limit
    std::vector<core::Vec3> w, u;       // transverse displacement [m] and velocity [m/s] of interior nodes
    core::Vec3 end_a, end_b;            // [m] world positions of the ends this step
    core::Vec3 velocity_a, velocity_b;  // [m/s] previous end velocities, for end accelerations
    core::Vec3 inertia_a, inertia_b;    // [N] the spring-carried rope's inertia on its ends (this step's)
    core::Vec3 damping_a,
        damping_b;  // [N] reaction of the wave's transverse damping on its ends (this step's)
    // [N] the bending hysteresis where the rope turns on the element at end A (B), pushing on end B (A)
    // across the chord; its reaction acts on end A's (B's) body at the same point (this step's)
    core::Vec3 bending_at_a, bending_at_b;
  };
  struct Rope {
    std::vector<int> segments;
    double stored_m = 0.0;  // [m] on its first drum (and last, if it ends on a drum)
  };
  struct ElementState {
    double omega = 0.0;        // [rad/s] positive moves rope from the drum towards the dead end
    double reference = 0.0;    // [rad/s] drum: ramped speed reference
    double rope_torque = 0.0;  // [N m] drum: torque from its ropes
  };

  const Segment& segment_at(int rope, int s) const { return segments_[ropes_[rope].segments[s]]; }
  double rope_speed_into(const Segment& s, bool at_a) const;
  void update_segment(Segment& s, const RopeSettings& rope, double dt, const CableBodies& bodies);
  void integrate_wave(Segment& s, const RopeSettings& rope, double dt, int substeps, const core::Vec3& e,
                      double h, double transport, const core::Vec3& accel_a, const core::Vec3& accel_b);
  core::Vec3 bending_force(const ElementSettings& element, const CableBodies& bodies, const core::Vec3& here,
                           const core::Vec3& there, const core::Vec3& velocity_here,
                           const core::Vec3& velocity_there, double loss_moment_n_m) const;
  void step_drums(double dt, std::span<const DrumCommand> commands);
  void step_sheaves(const Rope& rope, double dt);
  void apply_forces(const Segment& s, const RopeSettings& rope, CableBodies& bodies) const;
  void check_events(Segment& s, const RopeSettings& rope, int rope_index, int segment_index, double dt);
  std::uint32_t state_section() const;

  ReevingSettings settings_;
  core::Vec3 gravity_;
  std::vector<Segment> segments_;
  std::vector<Rope> ropes_;
  std::vector<ElementState> elements_;
  std::vector<int> drums_;  // element indices of drums, in order
  std::vector<CableEvent> events_;
  // scratch for the implicit transport solve (not state)
  std::vector<double> thomas_upper_, thomas_pivot_;
  std::vector<core::Vec3> thomas_rhs_;
  std::vector<double> sheave_lower_, sheave_diag_, sheave_upper_, sheave_rhs_;
};

}  // namespace harbour::cable
