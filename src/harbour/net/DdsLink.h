#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fastdds/rtps/common/InstanceHandle.h>

#include "harbour_console.h"  // generated from idl/harbour_console.idl by fastddsgen

namespace harbour::net {

/// The DDS topics of `idl/harbour_console.idl`.
inline constexpr const char* kStatusTopic = "harbour/station_status";
inline constexpr const char* kSceneTopic = "harbour/station_scene";
inline constexpr const char* kStateTopic = "harbour/station_state";
inline constexpr const char* kBulkTopic = "harbour/station_bulk";
inline constexpr const char* kPictureTopic = "harbour/station_picture";
inline constexpr const char* kEventTopic = "harbour/station_event";
inline constexpr const char* kCommandTopic = "harbour/station_command";
inline constexpr const char* kAckTopic = "harbour/command_ack";
inline constexpr const char* kTeamTopic = "harbour/team_state";
inline constexpr const char* kHandOffTopic = "harbour/team_hand_off";
inline constexpr const char* kChannelFrameTopic = "harbour/channel_frame";
inline constexpr const char* kChannelReadyTopic = "harbour/channel_ready";
inline constexpr const char* kChannelTileTopic = "harbour/channel_bulk_tile";

/// How often a station says it is there, and how long a console waits before it shows it as lost.
inline constexpr double kStatusPeriod_s = 0.5;
inline constexpr double kLostAfter_s = 3.0;

/// The key of a station's status instance: the 64-bit FNV-1a hash of its name. Eight bytes, so the RTPS key
/// hash is the key itself and any DDS implementation can take it back from a dispose (a string key over 16
/// bytes travels as an MD5 digest that no reader can reverse).
std::uint64_t station_key(const std::string& station);

/// Why `name` cannot name a station or a console on the network ("" when it can): 1 to 64 characters of
/// letters, digits, '-', '_' and '.'.
std::string why_bad_node_name(const std::string& name);

struct Participant;

/// A station's side of the centre's network: it publishes its status, scene, state, bulk and events and takes
/// the commands addressed to it, answering each. Thread-safe.
class StationLink {
 public:
  /// Joins DDS domain `domain` (0-232) as station `station`; throws std::runtime_error saying what failed.
  StationLink(const std::string& station, int domain);
  /// Disposes the station's status: consoles show it as gone at once (a killed process is seen as lost).
  ~StationLink();
  StationLink(const StationLink&) = delete;
  StationLink& operator=(const StationLink&) = delete;

  const std::string& name() const { return station_; }
  /// Each fills in the station's name (and an event its sequence number) before it is written.
  void publish(StationStatus status);
  void publish(StationScene scene);
  void publish(StationState state);
  void publish(StationBulk bulk);
  void publish(StationPicture picture);
  void publish(StationEvent event);
  /// The commands for this station that arrived since the last call, in order.
  std::vector<StationCommand> take_commands();
  void acknowledge(const StationCommand& command, bool ok, const std::string& message);

 private:
  std::string station_;
  std::unique_ptr<Participant> dds_;
  std::uint64_t status_sequence_ = 0, event_sequence_ = 0;
};

/// A team member's side of a team session: it publishes the state of the machine its station simulates and
/// takes the other members' (of the same session; its own and other sessions' are left out). Thread-safe.
class TeamLink {
 public:
  /// Joins DDS domain `domain` as station `station`, member `role` of team session `session`; throws
  /// std::runtime_error saying what failed.
  TeamLink(const std::string& station, const std::string& session, const std::string& role, int domain);
  ~TeamLink();
  TeamLink(const TeamLink&) = delete;
  TeamLink& operator=(const TeamLink&) = delete;

  /// Fills in the station, session, role and the time it is sent, and writes it.
  void publish(TeamState state);
  /// The other members' samples that arrived since the last call, in arrival order.
  std::vector<TeamState> take();
  /// Fills in the session, the sender's role as from_role (an offer) or to_role (acquired) and the time, and
  /// writes it.
  void hand_off(TeamHandOff message);
  /// The hand-off messages of this session that arrived since the last call, in arrival order.
  std::vector<TeamHandOff> take_hand_offs();
  /// Waits up to `timeout` for a sample to take (any member's, this session's or not); true when one came.
  bool wait(std::chrono::nanoseconds timeout);
  /// The monotonic clock TeamState::sent_ns is read from (one for every process on a host).
  static std::int64_t monotonic_ns();

 private:
  std::string station_, session_, role_;
  std::unique_ptr<Participant> dds_;
};

/// A console's side: every station on the domain, its newest status, scene and state, the events, and
/// commands sent with their acknowledgements. Not thread-safe: one thread polls and sends.
class ConsoleLink {
 public:
  using Clock = std::chrono::steady_clock;
  struct Station {
    StationStatus status;
    Clock::time_point heard;  ///< when its last status arrived
    bool lost = false;        ///< no status for kLostAfter_s (its process gone or its network)
    bool gone = false;        ///< it left the network in order
    std::optional<StationScene> scene;
    std::uint64_t scene_count =
        0;  ///< scenes received (an attempt's is sent again when an entity is renamed)
    std::optional<StationState> state;
    std::uint64_t state_count = 0;    ///< states received (the console's rate figures)
    std::optional<StationBulk> bulk;  ///< its bulk material's surfaces (bulk exercises)
    std::uint64_t bulk_count = 0;
    std::optional<StationPicture> picture;  ///< its trainee's cab view, newest
    std::uint64_t picture_count = 0;
    eprosima::fastrtps::rtps::InstanceHandle_t instance;  ///< its status instance (to see it disposed)
  };

  ConsoleLink(const std::string& console, int domain);
  ~ConsoleLink();
  ConsoleLink(const ConsoleLink&) = delete;
  ConsoleLink& operator=(const ConsoleLink&) = delete;

  const std::string& name() const { return console_; }
  /// Takes everything that arrived; marks stations lost. Returns the stations whose status, scene or
  /// lost flag changed.
  std::vector<std::string> poll(Clock::time_point now = Clock::now());
  const std::map<std::string, Station>& stations() const { return stations_; }
  /// Events since the last call, in arrival order.
  std::vector<StationEvent> take_events();
  /// Sends a command (its console and id filled in here) and returns its id.
  std::uint64_t send(StationCommand command);
  /// The acknowledgement of command `id`, once it has arrived (taken out).
  std::optional<CommandAck> take_ack(std::uint64_t id);

 private:
  std::string console_;
  std::unique_ptr<Participant> dds_;
  std::map<std::string, Station> stations_;
  std::vector<StationEvent> events_;
  std::map<std::uint64_t, CommandAck> acks_;
  std::uint64_t next_id_ = 1;
};

/// A station's side of its remote image-generator channels: it publishes the frames and the bulk tiles and
/// takes the channels' readiness. Thread-safe.
class ChannelServerLink {
 public:
  /// Joins DDS domain `domain` for station `station`'s channels; throws std::runtime_error saying what
  /// failed.
  ChannelServerLink(const std::string& station, int domain);
  ~ChannelServerLink();
  ChannelServerLink(const ChannelServerLink&) = delete;
  ChannelServerLink& operator=(const ChannelServerLink&) = delete;

  /// Each fills in the station's name before it is written.
  void publish(ChannelFrame frame);
  void publish(ChannelBulkTile tile);
  /// This station's channels' words since the last call, in arrival order.
  std::vector<ChannelReady> take_readies();

 private:
  std::string station_;
  std::unique_ptr<Participant> dds_;
};

/// A remote channel's side (`harboursim channel`): station `station`'s scene, frames and bulk tiles, and its
/// own readiness as display `display`. Thread-safe.
class ChannelFeed {
 public:
  ChannelFeed(const std::string& station, const std::string& display, int domain);
  ~ChannelFeed();
  ChannelFeed(const ChannelFeed&) = delete;
  ChannelFeed& operator=(const ChannelFeed&) = delete;

  /// The station's newest scene since the last call (an attempt's, or the same again with an entity renamed).
  std::optional<StationScene> take_scene();
  /// The newest frame since the last call into `frame`; false (untouched) when none came.
  bool take_frame(ChannelFrame& frame);
  /// Waits up to `timeout` for a frame to take; true when one came.
  bool wait_for_frame(std::chrono::nanoseconds timeout);
  /// The bulk tiles that changed since the last call, in arrival order.
  std::vector<ChannelBulkTile> take_tiles();
  /// Fills in the station and the display, and writes it.
  void ready(ChannelReady ready);
  /// Tells the station this channel stops drawing attempt `attempt` (it goes on without waiting for it), and
  /// waits up to `timeout` for the station to have it.
  void leave(std::int64_t attempt, std::chrono::milliseconds timeout = std::chrono::milliseconds(500));

 private:
  std::string station_, display_;
  std::unique_ptr<Participant> dds_;
};

}  // namespace harbour::net
