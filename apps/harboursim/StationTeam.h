#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "harbour/io/TeamFiles.h"
#include "harbour/net/DdsLink.h"
#include "harbour/station/TeamPresence.h"

namespace harbour::apps {

/// A team file by name (data/teams/NAME.yaml, or the centre's folder first) or path.
std::string resolve_team(const std::string& name_or_path, const std::string& centre_exercises = "");

/// A station's place in a team session: it publishes its machine's bodies at 50 Hz (velocities from
/// consecutive snapshots), takes the other members' and draws their machines in its scene (station::
/// TeamPresence), and says when a member is lost or back.
class TeamMembership {
 public:
  /// Builds the other roles' exercises here (without stepping them) for their machines' bodies and start
  /// poses; joins the session's DDS domain as `station`.
  TeamMembership(const io::Team& team, const std::string& role, const std::string& station, int domain,
                 const sim::SceneDescription& own_scene);
  ~TeamMembership();
  TeamMembership(const TeamMembership&) = delete;
  TeamMembership& operator=(const TeamMembership&) = delete;

  /// The station's scene with the other members' bodies after its own entities.
  const sim::SceneDescription& scene() const { return presence_.scene(); }
  /// Writes the members' bodies where they are now into `snapshot` (the loop's addition, on its step thread).
  void add_to(sim::Snapshot& snapshot) const;
  /// Starts publishing this machine from `latest` (the loop's team snapshots) and taking the others'; `said`
  /// hears "tractor: lost" and "tractor: back" (from this thread, as it happens).
  void start(std::function<const sim::Snapshot*()> latest, std::function<void(const std::string&)> said);
  void stop();
  /// One line per member: samples heard, their age on arrival, lost or not.
  std::vector<std::string> report();
  /// The team session this member was part of: "TEAM@START", START the earliest start (UTC, ISO 8601) of this
  /// member and every member it heard — what each member that heard the others stores with its attempt.
  std::string session() const;
  /// Every member together, after stop(): the near misses, the contacts, the closest approach (-1: none
  /// measured).
  struct Figures {
    int near_misses = 0, contacts = 0;
    double closest_m = -1.0;
  };
  Figures figures() const;

 private:
  void run();
  void take();  // the others' states that came, and who was lost or came back
  static double now_s();
  io::Team team_;
  std::string role_;
  int own_bodies_;
  net::TeamLink link_;
  station::TeamPresence presence_;
  std::function<const sim::Snapshot*()> latest_;
  std::function<void(const std::string&)> said_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::int64_t published_ = 0;
  std::int64_t started_unix_ms_;                // this member's start
  std::atomic<std::int64_t> earliest_unix_ms_;  // of this member's and every start heard
  std::set<std::string> refused_;               // the refusals said so far
  std::set<std::string> joined_;                // the roles heard so far
  station::NearMissWatch near_misses_;
};

}  // namespace harbour::apps
