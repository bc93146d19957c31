#pragma once

#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::station {

/// A body of a remote machine as its own station last published it (harbour frame).
struct RemoteMotion {
  core::Pose pose;
  core::Vec3 velocity_mps;
  core::Vec3 angular_velocity_radps;
};

/// Dead reckoning of one remote body between its samples: the newest sample carried on at its velocity and
/// angular velocity (for at most `horizon_s`: a body that falls silent stops where it would have been), and
/// each new sample blended in over `blend_s` from where the old one had carried it, so nothing jumps.
class DeadReckoning {
 public:
  DeadReckoning(double blend_s, double horizon_s) : blend_s_(blend_s), horizon_s_(horizon_s) {}
  /// Puts it at `motion` as of time `at_s`, with no blending (the first sample; a start pose).
  void place(const RemoteMotion& motion, double at_s);
  /// A new sample, valid at `at_s` (the receiver's clock).
  void update(const RemoteMotion& motion, double at_s);
  /// Where it is at `t_s` (the receiver's clock, at or after the last sample's time).
  core::Pose at(double t_s) const;
  /// The newest sample and its time.
  const RemoteMotion& newest() const { return new_; }
  double newest_at_s() const { return new_at_s_; }

 private:
  core::Pose carried(const RemoteMotion& m, double from_s, double t_s) const;
  double blend_s_, horizon_s_;
  RemoteMotion old_, new_;
  double old_at_s_ = 0.0, new_at_s_ = 0.0;
  bool blending_ = false;
};

/// The gap between two boxes (centre pose, half extents): the largest separation along the 15 axes of the
/// separating-axis test. Negative (the deepest overlap along the best axis) when they overlap; when apart a
/// lower bound on their distance, exact where the nearest features are faces (two boxes side by side).
double box_clearance(const core::Pose& a, const core::Vec3& half_a, const core::Pose& b,
                     const core::Vec3& half_b);

/// One other member of a team session as this station knows it before hearing from it: its role and its
/// machine's bodies (names, looks, sizes: the SceneDescription of its exercise) where its exercise starts
/// them.
struct TeamMember {
  std::string role;
  std::vector<scene::SceneDescription::Entity> bodies;
  std::vector<core::Pose> start_poses;  ///< one per body
  std::vector<bool> start_hidden;       ///< one per body: not there at the start (a load still to come)
  /// The first this many bodies are its machine's (the rest items it may hold: not counted as near misses)
  int machine_bodies = std::numeric_limits<int>::max();
};

/// What arrived from a member: its machine's bodies (by index into TeamMember::bodies) at one moment.
struct TeamSample {
  std::string role;
  double received_s = 0.0;  ///< the receiver's clock
  double age_s = -1.0;      ///< how old it was on arrival (measured where both share a clock; -1: unknown)
  std::vector<std::uint16_t> body;
  std::vector<RemoteMotion> motion;  ///< one per body index
};

/// The other members' machines at this station: added to its scene (after its own entities, each named
/// "ROLE: BODY"), dead-reckoned between their samples and written into every snapshot it publishes, so the
/// cab view, the console's 3D view and the chase view show them where their own stations have them. A body
/// missing from a member's newest sample is hidden (a member sends every body it draws: one it leaves out is
/// not there, as a load not yet handed over). A member not heard from for `lost_after_s` is lost: its machine
/// stays where it was last carried to. Thread-safe: samples are offered from the network side, snapshots
/// written on the step thread.
class TeamPresence {
 public:
  static constexpr double kBlend_s = 0.1;      ///< a new sample is blended in over this
  static constexpr double kHorizon_s = 0.5;    ///< dead reckoning carries a silent body on for at most this
  static constexpr double kLostAfter_s = 2.0;  ///< a member silent this long is lost

  TeamPresence(const scene::SceneDescription& own_scene, std::vector<TeamMember> members);

  /// The station's scene with the members' bodies after its own entities.
  const scene::SceneDescription& scene() const { return scene_; }
  /// Takes a member's sample; one of a role not in the team, or with a body index it lacks, is refused with
  /// the reason ("" when taken).
  std::string offer(const TeamSample& sample);
  /// Appends the members' bodies, where they are at `now_s` (the receiver's clock), to `snapshot`.
  void write(scene::Snapshot& snapshot, double now_s) const;
  /// Body `body` of member `role` at `now_s`: where it is carried to, at its newest sample's velocities (at
  /// rest where it starts until heard); nullopt for a role or body the team lacks.
  std::optional<RemoteMotion> motion_of(const std::string& role, int body, double now_s) const;

  /// The closest approach of a member's machine to this station's, at `now_s`: which bodies, how far.
  struct Closest {
    std::string role;
    std::string own_body, member_body;
    double clearance_m = 0.0;  ///< box_clearance (negative: they overlap)
  };
  /// For each member, its bodies against this station's machine bodies as `own` has them (bodies with no size
  /// in the scene are left out: a gantry drawn from its looks alone).
  std::vector<Closest> closest(const scene::Snapshot& own, double now_s) const;

  struct MemberState {
    std::string role;
    bool heard = false;  ///< a sample has arrived
    bool lost = false;   ///< heard, then silent for kLostAfter_s
    bool left = false;   ///< it said it left (its attempt ended): not lost
    std::int64_t samples = 0;
    std::int64_t measured = 0;  ///< samples whose age on arrival was measured
    double age_p50_s = 0.0, age_p99_s = 0.0, age_max_s = 0.0;
  };
  /// Each member as of `now_s`; `changed` gets the roles that were lost or came back since the last call.
  /// The ages' quantiles only `with_ages` (they sort every age so far).
  std::vector<MemberState> members(double now_s, std::vector<std::string>* changed = nullptr,
                                   bool with_ages = false);
  /// Member `role` left in order (its attempt ended): it stays where it was, and is not reported lost.
  void left(const std::string& role);
  /// Each member as known before hearing from it (its bodies and their sizes), in the team's order.
  std::vector<TeamMember> known() const;
  /// Body `body` of member `role` is drawn: in its newest sample (as its exercise starts it until heard) and
  /// its member has not left.
  bool there(const std::string& role, int body) const;

 private:
  struct Member {
    TeamMember known;
    std::vector<DeadReckoning> bodies;
    std::vector<bool> present;  // in its newest sample (before any: as it starts)
    int first_entity = 0;       // its first body's index in scene_
    MemberState state;
    std::vector<double> ages_s;  // each measured sample's age on arrival
    double last_heard_s = 0.0;
  };
  scene::SceneDescription scene_;
  std::vector<Member> members_;
  mutable std::mutex mutex_;
};

/// Near misses between this station's machine and the other members': an episode starts when a member's
/// clearance falls below kNearMiss_m and ends when it is back above kClear_m (a machine hovering about the
/// threshold is one near miss, not many); boxes that touch are a contact, said once per episode.
class NearMissWatch {
 public:
  static constexpr double kNearMiss_m = 1.0;
  static constexpr double kClear_m = 1.5;
  /// The closest approaches now; returns what to tell ("near miss: spreader 0.42 m from tractor: trailer",
  /// "contact: spreader with tractor: trailer").
  std::vector<std::string> update(const std::vector<TeamPresence::Closest>& closest);
  struct Tally {
    std::string role;
    int near_misses = 0, contacts = 0;
    double closest_m = 1e300;  ///< the smallest clearance seen
  };
  const std::vector<Tally>& tallies() const { return tallies_; }

 private:
  struct Episode {
    bool near = false, touched = false;
  };
  std::vector<Tally> tallies_;
  std::vector<Episode> episodes_;  // by tally
};

}  // namespace harbour::station
