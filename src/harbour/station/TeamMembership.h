#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "harbour/io/TeamFiles.h"
#include "harbour/net/DdsLink.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/station/TeamPresence.h"

namespace harbour::station {

/// What another machine can hit of a look beyond its entity's own box (ig::VisualPart::solid): boxes in the
/// entity's frame, by look key (an STS's legs under "sts.gantry").
struct SolidPart {
  core::Pose local;
  core::Vec3 half_extents_m;
};
using SolidParts = std::map<std::string, std::vector<SolidPart>>;

/// A team file by name (data/teams/NAME.yaml, or the centre's folder first) or path.
std::string resolve_team(const std::string& name_or_path, const std::string& centre_exercises = "");

/// A station's place in a team session: it publishes its machine's bodies at 50 Hz (velocities from
/// consecutive snapshots), takes the other members' and draws their machines in its scene (
/// TeamPresence), and says when a member is lost or back. A crane with team trucks feeds its simulation where
/// their tractors' trailers are (sim::TeamInput::kTruckAt, 50 Hz) and hands each box seated on one to that
/// tractor's station: it offers the box every 100 ms until the tractor says it has acquired it, then lets it
/// go (kTakenOver). A tractor takes a box offered to it onto its trailer (kLoadOn) and answers every offer.
/// Every member's simulation has the others' machine bodies with a size (a tractor, a trailer, a spreader;
/// at a crane its team trucks' trailers are its decks already) and their looks' solid parts (an STS's legs)
/// as obstacles it can hit (kObstacleAt).
class TeamMembership {
 public:
  /// Builds the other roles' exercises here (without stepping them) for their machines' bodies and start
  /// poses; joins the session's DDS domain as `station`. Throws std::runtime_error when the team's trucks do
  /// not fit the exercises (a crane's lane of another size, a truck role whose trailer takes no box).
  /// `time_scale`: the session's clock runs so much faster than the wall's (every member runs at it).
  TeamMembership(const io::Team& team, const std::string& role, const std::string& station, int domain,
                 const sim::ExerciseSettings& own_exercise, const scene::SceneDescription& own_scene,
                 double time_scale = 1.0, const SolidParts& solid = {});
  ~TeamMembership();
  TeamMembership(const TeamMembership&) = delete;
  TeamMembership& operator=(const TeamMembership&) = delete;

  /// The station's scene with the other members' bodies after its own entities.
  const scene::SceneDescription& scene() const { return presence_.scene(); }
  /// Writes the members' bodies where they are now into `snapshot` (the loop's addition, on its step thread).
  void add_to(scene::Snapshot& snapshot) const;
  /// Starts publishing this machine from `latest` (the loop's team snapshots) and taking the others'; `said`
  /// hears "tractor: lost" and "tractor: back" (from this thread, as it happens).
  /// `input` posts a team input to the station's loop (false: refused, to be tried again). `load_named`
  /// hears, at a tractor, its load entity's index and the id of the box handed over onto it (its pictures
  /// then draw the box as the crane's did).
  void start(std::function<const scene::Snapshot*()> latest, std::function<void(const std::string&)> said,
             std::function<bool(const sim::TeamInput&)> input,
             std::function<void(int entity, const std::string& id)> load_named = {});
  void stop();
  /// After stop(), as the attempt ends: tells the others this member leaves in order (they say "left", not
  /// "lost").
  void leave();
  /// One line per member: samples heard, their age on arrival, lost or not.
  std::vector<std::string> report();
  /// The team session this member was part of: "TEAM@START", START the earliest start (UTC, ISO 8601) of this
  /// member and every member it heard — what each member that heard the others stores with its attempt.
  std::string session() const;
  /// What this member measured of the team, after stop(): the near misses, the contacts and the closest
  /// approach of every member; the boxes handed over, to or from it; a tractor's wait at its load stop.
  sim::TeamFigures figures() const;

 private:
  void run();
  void take();  // the others' states that came, and who was lost or came back
  void take_hand_offs();
  void feed_trucks();     // a crane: where its team trucks are, into its simulation
  void feed_obstacles();  // the others' machine bodies, into its simulation as obstacles
  void offer_seated(const scene::Snapshot& s);  // a crane: the boxes on its trucks, offered to their tractors
  void watch_load_stop(const scene::Snapshot& s);  // a tractor: how long it stood waiting for its box
  static double wall_s();
  double now_s() const;  // the session's clock: the wall's at the time scale
  io::Team team_;
  std::string role_;
  double time_scale_;
  int own_bodies_;    // its machine's: sent every period
  int own_entities_;  // its scene's (the items it holds are sent while it holds them)
  net::TeamLink link_;
  TeamPresence presence_;
  std::function<const scene::Snapshot*()> latest_;
  std::function<void(int, const std::string&)> load_named_;
  std::function<void(const std::string&)> said_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::int64_t published_ = 0;
  std::int64_t started_unix_ms_;                // this member's start
  std::atomic<std::int64_t> earliest_unix_ms_;  // of this member's and every start heard
  std::set<std::string> refused_;               // the refusals said so far
  std::set<std::string> joined_;                // the roles heard so far
  std::set<std::string> left_;                  // the roles that said they left
  NearMissWatch near_misses_;
  std::function<bool(const sim::TeamInput&)> input_;
  // the last input given for a remote body, and when (the session's clock)
  struct Fed {
    std::optional<sim::TeamInput> input;
    double at_s = 0.0;
  };
  void give(Fed& fed, const sim::TeamInput& in, double now_s);  // to the simulation, noted where taken
  // a crane's team trucks: the tractors' roles, their trailers' bodies and decks; the crane's own boxes
  struct Truck {
    std::string role;
    int trailer_body = -1;       // in the member's bodies
    double deck_half_z_m = 0.0;  // its deck's top above its centre
    Fed fed;
    int entity = -1;  // the crane's team truck in its own scene
  };
  std::vector<Truck> trucks_;
  // the others' machine bodies with a size and their looks' solid parts, each obstacle of this simulation
  // (its slot: its place here)
  struct Obstacle {
    std::string role;
    int body = -1;     // in the member's bodies
    core::Pose local;  // in the body's frame
    core::Vec3 half_extents_m;
    Fed fed;
  };
  std::vector<Obstacle> obstacles_;
  std::map<std::string, double> box_mass_kg_;  // by id
  struct Offer {
    int truck = -1;
    double first_s = 0.0, last_s = -1.0;  // when first and last offered (wall clock)
    net::TeamHandOff message;
    bool settled = false;
  };
  std::map<std::string, Offer> offers_;  // by box id
  std::set<std::string> acquired_;       // a tractor's boxes taken on
  int hand_offs_ = 0;
  double worst_hand_off_s_ = -1.0;
  // a tractor's load stop: where its trailer stands to be loaded, and its own trailer and load entities
  std::optional<sim::LoadStop> load_stop_;
  int trailer_entity_ = -1, load_entity_ = -1;
  core::Vec3 trailer_was_;
  double trailer_was_s_ = -1.0, standing_since_s_ = -1.0, waited_s_ = -1.0;
};

}  // namespace harbour::station
