#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

#include "harbour/audio/SoundThread.h"
#include "harbour/net/DdsLink.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/station/Session.h"

namespace harbour::station {

/// The instructor's picture of the trainee's cab view: its size, rate and largest JPEG (the topic's bound).
inline constexpr int kPictureWidth = 640, kPictureHeight = 360;
inline constexpr double kPicturesPerSecond = 5.0;
inline constexpr std::size_t kMostPictureBytes = 262144;
/// How an attempt ended, in the words the console shows: "attempt 5 passed, score 87.0", "attempt 6 ended by
/// the instructor, score 40.2", "attempt 7 interrupted".
std::string attempt_outcome(const SessionResult& result);

/// What a console asked a station to do next (run an exercise, or nothing new).
struct StartRequest {
  std::string exercise, trainee, user;
  std::string route;  ///< a training route: the trainee's next stage of it (the exercise then names it)
  std::string team,
      role;  ///< a member of a team session (a shipped team's name), running its role's exercise
  bool autopilot = false;
  std::optional<TakeOverFrom> take_over;  ///< continue a stored attempt from a moment
};

/// A station's presence on the centre's network while idle: its status at 2 Hz and the commands it takes
/// (start, take-over; anything else is refused, nothing runs).
class IdlePresence {
 public:
  IdlePresence(net::StationLink& link, const std::string& last_message);
  /// Publishes what is due and answers commands; a start request when one came.
  std::optional<StartRequest> service();

 private:
  net::StationLink& link_;
  std::string message_;
  std::chrono::steady_clock::time_point next_status_{};
};

/// A station's presence while an attempt runs: status at 2 Hz (and at once on every change), the scene
/// once, the published state at 10 Hz, the evaluation's events as they are counted, and the console's
/// commands applied to the running loop (each acknowledged).
class AttemptPresence {
 public:
  enum class Next { kRun, kStop, kReset };
  /// `scene`: what the station draws (its simulation's scene, and a team's other machines after it).
  AttemptPresence(net::StationLink& link, Session& session, const sim::ExerciseSettings& exercise,
                  const std::string& trainee, const scene::SceneDescription& scene);
  /// Publishes what is due and applies the commands that came; says whether the attempt goes on.
  Next service();
  /// Tells the consoles how the attempt ended.
  void publish_end(const SessionResult& result);
  /// A line for the consoles' event logs (a device lost, the image generator stopped). Call from the
  /// thread that calls service() (it reads the console's snapshots).
  void note(const std::string& kind, const std::string& text);
  /// Entity `index` of the attempt's scene is now `name` (a box handed over onto this station's load): the
  /// scene is published again, so the consoles' 3D views draw it with its own paint.
  void rename_entity(std::size_t index, const std::string& name);
  /// The trainee's cab view as the instructor sees it, a JPEG picture drawn at simulated time `time_s`: sent
  /// with the next service() (any thread; a newer one replaces one not yet sent).
  void offer_picture(std::vector<std::uint8_t> jpeg, int width, int height, double time_s);
  /// A console shows this station now (its last `watch` command less than kWatchedFor ago): the pictures are
  /// drawn only then (any thread).
  bool watched() const {
    return std::chrono::steady_clock::now().time_since_epoch().count() < watched_until_ns_.load();
  }
  static constexpr std::chrono::seconds kWatchedFor{5};
  /// The station's sound, which the console may mute or turn up and down (`mute`, `unmute`,
  /// `volume:PERCENT`); none: those commands are refused.
  void use_sound(audio::SoundThread* sound) { sound_ = sound; }

  /// The attempt is a team session's member: said in every status.
  void member_of(const std::string& team, const std::string& role) {
    team_ = team;
    role_ = role;
  }

 private:
  net::StationStatus status(const std::string& state, const scene::Snapshot* snapshot) const;
  const scene::Snapshot* snapshot();  // the console reader's newest (one reader: this thread)
  void publish_state(const scene::Snapshot& snapshot);
  double published_time_s();  // the simulated time of the newest snapshot (not the stepping simulation's)
  bool apply(const net::StationCommand& command, std::string& answer, Next& next);
  bool apply_sound(const std::string& kind, std::string& answer);
  /// Calls a signal on the radio where it can: "done: the operator sees "stop" and hears it on the radio", or
  /// why it is only shown.
  std::string say_signal(const sim::InstructorCommand& command);

  net::StationLink& link_;
  Session& session_;
  const sim::ExerciseSettings& exercise_;
  std::string trainee_;
  std::string team_, role_;
  scene::SceneDescription scene_;
  sim::Metrics seen_;
  bool was_held_ = false;
  std::chrono::steady_clock::time_point next_status_{}, next_state_{}, next_bulk_{};
  std::atomic<std::chrono::steady_clock::rep> watched_until_ns_{0};
  std::mutex picture_mutex_;
  std::optional<net::StationPicture> picture_;  // offered, not yet sent
  audio::SoundThread* sound_ = nullptr;
};

}  // namespace harbour::station
