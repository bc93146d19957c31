#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harbour/scene/Snapshot.h"
#include "harbour/sim/Recording.h"

namespace harbour::sim {

/// A team session replayed as a whole: each member's recording re-simulated by its own ReplayPlayer on the
/// session's clock (each from the moment it started, after the first member), drawn as one scene: every
/// member's entities, each where its own simulation has it and hidden where that one hides it — so a box is
/// drawn by its crane until it is handed over and by its tractor after, never twice. A single attempt is a
/// session of one.
class SessionPlayer {
 public:
  struct Member {
    std::string role;  ///< "" for an attempt alone
    ScenarioSettings scenario;
    Recording recording;
    double start_s = 0.0;  ///< when it started on the session's clock (the earliest at 0)
  };
  /// Members in drawing order: the first gives the scene its environment, cab, indicators and machine.
  /// Throws (naming the role) where a member's recording does not fit its scenario.
  explicit SessionPlayer(std::vector<Member> members);
  ~SessionPlayer();

  /// The members' entities, a truck's "load" named after the box handed onto it by then (handed_load_name).
  const scene::SceneDescription& scene() const { return scene_; }
  /// Counts the changes of the scene's names (a box handed onto a truck, or seeking back before it).
  std::uint64_t names_version() const { return names_version_; }
  double duration_s() const { return duration_s_; }
  /// The session's clock: where it has been taken to.
  double time_s() const { return time_s_; }
  /// Each member at `t_s` of the session (one that has not started yet at its start; one that has ended at
  /// its end): from the keyframe before, then re-simulated.
  void seek(double t_s);
  /// Each member re-simulated on to `t_s` (later than now).
  void advance_to(double t_s);
  /// The whole scene now: the first member's snapshot with every other member's entities (indexed after the
  /// entities before theirs in scene()) and ropes added.
  void write_snapshot(scene::Snapshot& out) const;
  /// The first step at which a member's re-simulation left its recording, with its role.
  std::optional<std::pair<std::string, std::int64_t>> first_mismatch() const;
  std::size_t members() const { return members_.size(); }
  const Member& member(std::size_t k) const { return members_[k]; }
  const ReplayPlayer& player(std::size_t k) const { return *players_[k]; }
  ReplayPlayer& player(std::size_t k) { return *players_[k]; }

 private:
  std::int64_t member_step(std::size_t k, double t_s) const;
  void name_loads();  // each truck's load as handed then

  std::vector<Member> members_;  // each recording stays where it is: its player refers to it
  std::vector<std::unique_ptr<ReplayPlayer>> players_;
  std::vector<int> first_entity_;  // of each member in scene_
  std::vector<int> load_entity_;   // each member's "load" in scene_, -1 where it has none
  std::uint64_t names_version_ = 0;
  scene::SceneDescription scene_;
  std::unique_ptr<scene::Snapshot> member_snapshot_ = std::make_unique<scene::Snapshot>();
  double duration_s_ = 0.0, time_s_ = 0.0;
};

/// When a truck's member started on its crane's clock, from the hand-off both recorded (the crane: the box on
/// its team truck `slot` taken over; the truck: a load set on its trailer), which happened together within an
/// offer's flight: the crane's step less the truck's. Nullopt where either has none.
std::optional<double> truck_start_s(const Recording& crane, int slot, const Recording& truck);

}  // namespace harbour::sim
