#include "harbour/net/DdsLink.h"

#include <algorithm>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <mutex>
#include <stdexcept>

#include "harbour_consolePubSubTypes.h"

namespace harbour::net {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

std::uint64_t station_key(const std::string& station) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : station) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string why_bad_node_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return "1 to 64 characters";
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
          c == '_' || c == '.'))
      return "letters, digits, '-', '_' and '.' only";
  return "";
}

namespace {

enum class Delivery { kLatestKept, kStream, kBestEffort };

constexpr int kMostNodes = 256;  // stations and consoles on one domain
constexpr int kHandOffDepth =
    64;  // hand-off messages kept for a late reader (re-offered every 100 ms anyway)

// a writer's or a reader's QoS for one of the three kinds of delivery
template <class Qos>
Qos endpoint_qos(Qos q, Delivery delivery, int depth, int instances) {
  q.reliability().kind =
      delivery == Delivery::kBestEffort ? dds::BEST_EFFORT_RELIABILITY_QOS : dds::RELIABLE_RELIABILITY_QOS;
  q.durability().kind =
      delivery == Delivery::kLatestKept ? dds::TRANSIENT_LOCAL_DURABILITY_QOS : dds::VOLATILE_DURABILITY_QOS;
  q.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  q.history().depth = depth;
  // one instance per station or console (Fast DDS's default allows 10)
  q.resource_limits().max_instances = instances;
  q.resource_limits().max_samples_per_instance = depth;
  q.resource_limits().max_samples = instances * depth;
  // the big samples (scene, state) are not preallocated at their bound for every slot
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
  return q;
}

// Events and commands may come in bursts (an instructor's several clicks, a collision series): deep enough
// histories that none is dropped (KEEP_LAST 1 drops samples under bursts).
constexpr int kEventDepth = 256, kCommandDepth = 64, kAckDepth = 256;
// a channel's readiness comes once a frame; a station's bulk tiles are an instance each
constexpr int kReadyDepth = 8, kMostTiles = 8192;

}  // namespace

/// One DDS participant with the centre's topics.
struct Participant {
  dds::DomainParticipant* participant = nullptr;
  dds::Publisher* publisher = nullptr;
  dds::Subscriber* subscriber = nullptr;
  std::map<std::string, dds::Topic*> topics;
  dds::DataWriter *status = nullptr, *scene = nullptr, *state = nullptr, *bulk = nullptr, *picture = nullptr,
                  *event = nullptr, *command = nullptr, *ack = nullptr, *team = nullptr, *hand_off = nullptr,
                  *frame = nullptr, *ready = nullptr, *tile = nullptr;
  dds::DataReader *status_in = nullptr, *scene_in = nullptr, *state_in = nullptr, *bulk_in = nullptr,
                  *picture_in = nullptr, *event_in = nullptr, *command_in = nullptr, *ack_in = nullptr,
                  *team_in = nullptr, *hand_off_in = nullptr, *frame_in = nullptr, *ready_in = nullptr,
                  *tile_in = nullptr;
  std::mutex write_mutex;

  Participant(int domain, const std::string& name) {
    if (domain < 0 || domain > 232)
      throw std::runtime_error("DDS domain " + std::to_string(domain) + ": 0-232");
    dds::DomainParticipantQos qos = dds::PARTICIPANT_QOS_DEFAULT;
    qos.name(name);
    participant = dds::DomainParticipantFactory::get_instance()->create_participant(
        static_cast<dds::DomainId_t>(domain), qos);
    if (!participant) throw std::runtime_error("DDS: cannot join domain " + std::to_string(domain));
    register_type<StationStatusPubSubType>(kStatusTopic);
    register_type<StationScenePubSubType>(kSceneTopic);
    register_type<StationStatePubSubType>(kStateTopic);
    register_type<StationBulkPubSubType>(kBulkTopic);
    register_type<StationPicturePubSubType>(kPictureTopic);
    register_type<StationEventPubSubType>(kEventTopic);
    register_type<StationCommandPubSubType>(kCommandTopic);
    register_type<CommandAckPubSubType>(kAckTopic);
    register_type<TeamStatePubSubType>(kTeamTopic);
    register_type<TeamHandOffPubSubType>(kHandOffTopic);
    register_type<ChannelFramePubSubType>(kChannelFrameTopic);
    register_type<ChannelReadyPubSubType>(kChannelReadyTopic);
    register_type<ChannelBulkTilePubSubType>(kChannelTileTopic);
    publisher = participant->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber = participant->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    if (!publisher || !subscriber) fail("a publisher or subscriber");
  }
  ~Participant() {
    if (!participant) return;
    participant->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant);
  }

  template <class PubSubType>
  void register_type(const char* topic_name) {
    dds::TypeSupport type(new PubSubType());
    if (type.register_type(participant) != ReturnCode_t::RETCODE_OK) fail(topic_name);
    dds::Topic* topic = participant->create_topic(topic_name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    if (!topic) fail(topic_name);
    topics[topic_name] = topic;
  }
  dds::DataWriter* writer(const char* topic, Delivery delivery, int depth, int instances = kMostNodes) {
    dds::DataWriter* w = publisher->create_datawriter(
        topics.at(topic), endpoint_qos(dds::DATAWRITER_QOS_DEFAULT, delivery, depth, instances));
    if (!w) fail(std::string("a writer of ") + topic);
    return w;
  }
  dds::DataReader* reader(const char* topic, Delivery delivery, int depth, int instances = kMostNodes) {
    dds::DataReader* r = subscriber->create_datareader(
        topics.at(topic), endpoint_qos(dds::DATAREADER_QOS_DEFAULT, delivery, depth, instances));
    if (!r) fail(std::string("a reader of ") + topic);
    return r;
  }
  [[noreturn]] void fail(const std::string& what) { throw std::runtime_error("DDS: cannot create " + what); }

  template <class Sample>
  void write(dds::DataWriter* w, const Sample& sample) {
    std::lock_guard lock(write_mutex);
    w->write(const_cast<Sample*>(&sample));
  }
  // every valid sample waiting in `r`, and whether an instance was disposed (its key in `disposed`)
  template <class Sample, class Each>
  void take(dds::DataReader* r, Each each) {
    Sample sample;
    dds::SampleInfo info;
    while (r->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK)
      each(sample, info);
  }
};

StationLink::StationLink(const std::string& station, int domain) : station_(station) {
  if (const std::string why = why_bad_node_name(station); !why.empty())
    throw std::runtime_error("station name '" + station + "': " + why);
  dds_ = std::make_unique<Participant>(domain, "harbour station " + station);
  dds_->status = dds_->writer(kStatusTopic, Delivery::kLatestKept, 1);
  dds_->scene = dds_->writer(kSceneTopic, Delivery::kLatestKept, 1);
  dds_->state = dds_->writer(kStateTopic, Delivery::kBestEffort, 1);
  dds_->bulk = dds_->writer(kBulkTopic, Delivery::kBestEffort, 1);
  dds_->picture = dds_->writer(kPictureTopic, Delivery::kBestEffort, 1);
  dds_->event = dds_->writer(kEventTopic, Delivery::kStream, kEventDepth);
  dds_->ack = dds_->writer(kAckTopic, Delivery::kStream, kAckDepth);
  // every station reads every command and keeps its own (a content filter would need the types' TypeObject)
  dds_->command_in = dds_->reader(kCommandTopic, Delivery::kStream, kCommandDepth);
}

StationLink::~StationLink() {
  StationStatus key;
  key.station_key(station_key(station_));
  std::lock_guard lock(dds_->write_mutex);
  dds_->status->dispose(&key, dds_->status->lookup_instance(&key));
  // reliable: let the consoles have it before the participant goes
  dds_->status->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(1, 0));
}

void StationLink::publish(StationStatus status) {
  status.station_key(station_key(station_));
  status.station(station_);
  status.sequence_number(++status_sequence_);
  dds_->write(dds_->status, status);
}
void StationLink::publish(StationScene scene) {
  scene.station(station_);
  dds_->write(dds_->scene, scene);
}
void StationLink::publish(StationState state) {
  state.station(station_);
  dds_->write(dds_->state, state);
}
void StationLink::publish(StationBulk bulk) {
  bulk.station(station_);
  dds_->write(dds_->bulk, bulk);
}

void StationLink::publish(StationPicture picture) {
  picture.station(station_);
  dds_->write(dds_->picture, picture);
}
void StationLink::publish(StationEvent event) {
  event.station(station_);
  event.sequence_number(++event_sequence_);
  dds_->write(dds_->event, event);
}

std::vector<StationCommand> StationLink::take_commands() {
  std::vector<StationCommand> commands;
  dds_->take<StationCommand>(dds_->command_in, [&](const StationCommand& c, const dds::SampleInfo& info) {
    if (info.valid_data && c.station().to_string() == station_) commands.push_back(c);
  });
  return commands;
}

void StationLink::acknowledge(const StationCommand& command, bool ok, const std::string& message) {
  CommandAck ack;
  ack.console(command.console());
  ack.id(command.id());
  ack.station(station_);
  ack.ok(ok);
  ack.message(message.substr(0, 255));
  dds_->write(dds_->ack, ack);
}

TeamLink::TeamLink(const std::string& station, const std::string& session, const std::string& role,
                   int domain)
    : station_(station), session_(session), role_(role) {
  if (const std::string why = why_bad_node_name(station); !why.empty())
    throw std::runtime_error("station name '" + station + "': " + why);
  if (session.empty() || session.size() > 64)
    throw std::runtime_error("team session '" + session + "': 1 to 64 characters");
  if (role.empty() || role.size() > 32)
    throw std::runtime_error("team role '" + role + "': 1 to 32 characters");
  dds_ = std::make_unique<Participant>(domain, "harbour team member " + station);
  dds_->team = dds_->writer(kTeamTopic, Delivery::kBestEffort, 1);
  dds_->team_in = dds_->reader(kTeamTopic, Delivery::kBestEffort, 1);
  dds_->hand_off = dds_->writer(kHandOffTopic, Delivery::kStream, kHandOffDepth);
  dds_->hand_off_in = dds_->reader(kHandOffTopic, Delivery::kStream, kHandOffDepth);
}

void TeamLink::hand_off(TeamHandOff message) {
  message.session(session_);
  (message.kind() == 0 ? message.from_role() : message.to_role()) = role_;
  message.sent_ns(monotonic_ns());
  dds_->write(dds_->hand_off, message);
}

std::vector<TeamHandOff> TeamLink::take_hand_offs() {
  std::vector<TeamHandOff> messages;
  dds_->take<TeamHandOff>(dds_->hand_off_in, [&](const TeamHandOff& m, const dds::SampleInfo& info) {
    if (info.valid_data && m.session().to_string() == session_) messages.push_back(m);
  });
  return messages;
}

TeamLink::~TeamLink() = default;

std::int64_t TeamLink::monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void TeamLink::publish(TeamState state) {
  state.station(station_);
  state.session(session_);
  state.role(role_);
  state.sent_ns(monotonic_ns());
  dds_->write(dds_->team, state);
}

bool TeamLink::wait(std::chrono::nanoseconds timeout) {
  const std::int64_t ns = std::max<std::int64_t>(timeout.count(), 0);
  return dds_->team_in->wait_for_unread_message(eprosima::fastrtps::Duration_t(
      static_cast<std::int32_t>(ns / 1000000000), static_cast<std::uint32_t>(ns % 1000000000)));
}

std::vector<TeamState> TeamLink::take() {
  std::vector<TeamState> states;
  dds_->take<TeamState>(dds_->team_in, [&](const TeamState& t, const dds::SampleInfo& info) {
    if (info.valid_data && t.session().to_string() == session_ && t.station().to_string() != station_)
      states.push_back(t);
  });
  return states;
}

ConsoleLink::ConsoleLink(const std::string& console, int domain) : console_(console) {
  if (const std::string why = why_bad_node_name(console); !why.empty())
    throw std::runtime_error("console name '" + console + "': " + why);
  dds_ = std::make_unique<Participant>(domain, "harbour console " + console);
  dds_->command = dds_->writer(kCommandTopic, Delivery::kStream, kCommandDepth);
  dds_->status_in = dds_->reader(kStatusTopic, Delivery::kLatestKept, 1);
  dds_->scene_in = dds_->reader(kSceneTopic, Delivery::kLatestKept, 1);
  dds_->state_in = dds_->reader(kStateTopic, Delivery::kBestEffort, 1);
  dds_->bulk_in = dds_->reader(kBulkTopic, Delivery::kBestEffort, 1);
  dds_->picture_in = dds_->reader(kPictureTopic, Delivery::kBestEffort, 1);
  dds_->event_in = dds_->reader(kEventTopic, Delivery::kStream, kEventDepth);
  dds_->ack_in = dds_->reader(kAckTopic, Delivery::kStream, kAckDepth);
}

ConsoleLink::~ConsoleLink() = default;

std::vector<std::string> ConsoleLink::poll(Clock::time_point now) {
  std::vector<std::string> changed;
  const auto note = [&](const std::string& name) {
    if (changed.empty() || changed.back() != name) changed.push_back(name);
  };
  dds_->take<StationStatus>(dds_->status_in, [&](const StationStatus& s, const dds::SampleInfo& info) {
    const std::string name = s.station().to_string();
    if (info.valid_data) {
      Station& station = stations_[name];
      station.status = s;
      station.instance = info.instance_handle;
      station.heard = now;
      station.lost = station.gone = false;
      note(name);
    } else if (info.instance_state == dds::NOT_ALIVE_DISPOSED_INSTANCE_STATE) {
      // an invalid sample carries only its instance (Fast DDS 2.9 does not give the key back from it)
      for (auto& [n, station] : stations_)
        if (station.instance == info.instance_handle && !station.gone) {
          station.gone = true;
          note(n);
        }
    }
  });
  dds_->take<StationScene>(dds_->scene_in, [&](const StationScene& s, const dds::SampleInfo& info) {
    if (!info.valid_data) return;
    Station& station = stations_[s.station().to_string()];
    station.scene = s;
    ++station.scene_count;
    note(s.station().to_string());
  });
  dds_->take<StationState>(dds_->state_in, [&](const StationState& s, const dds::SampleInfo& info) {
    if (!info.valid_data) return;
    Station& station = stations_[s.station().to_string()];
    station.state = s;
    ++station.state_count;
  });
  dds_->take<StationBulk>(dds_->bulk_in, [&](const StationBulk& b, const dds::SampleInfo& info) {
    if (!info.valid_data) return;
    Station& station = stations_[b.station().to_string()];
    station.bulk = b;
    ++station.bulk_count;
  });
  dds_->take<StationPicture>(dds_->picture_in, [&](const StationPicture& p, const dds::SampleInfo& info) {
    if (!info.valid_data) return;
    Station& station = stations_[p.station().to_string()];
    station.picture = p;
    ++station.picture_count;
  });
  dds_->take<StationEvent>(dds_->event_in, [&](const StationEvent& e, const dds::SampleInfo& info) {
    if (info.valid_data) events_.push_back(e);
  });
  dds_->take<CommandAck>(dds_->ack_in, [&](const CommandAck& a, const dds::SampleInfo& info) {
    if (info.valid_data && a.console().to_string() == console_) acks_[a.id()] = a;
  });
  for (auto& [name, station] : stations_) {
    const bool lost =
        !station.gone && std::chrono::duration<double>(now - station.heard).count() > kLostAfter_s;
    if (lost != station.lost) {
      station.lost = lost;
      note(name);
    }
  }
  return changed;
}

std::vector<StationEvent> ConsoleLink::take_events() {
  std::vector<StationEvent> events;
  events.swap(events_);
  return events;
}

std::uint64_t ConsoleLink::send(StationCommand command) {
  command.console(console_);
  command.id(next_id_++);
  dds_->write(dds_->command, command);
  return command.id();
}

std::optional<CommandAck> ConsoleLink::take_ack(std::uint64_t id) {
  const auto found = acks_.find(id);
  if (found == acks_.end()) return std::nullopt;
  CommandAck ack = found->second;
  acks_.erase(found);
  return ack;
}

ChannelServerLink::ChannelServerLink(const std::string& station, int domain) : station_(station) {
  if (const std::string why = why_bad_node_name(station); !why.empty())
    throw std::runtime_error("station name '" + station + "': " + why);
  dds_ = std::make_unique<Participant>(domain, "harbour channels of " + station);
  dds_->frame = dds_->writer(kChannelFrameTopic, Delivery::kLatestKept, 1);
  dds_->tile = dds_->writer(kChannelTileTopic, Delivery::kLatestKept, 1, kMostTiles);
  dds_->ready_in = dds_->reader(kChannelReadyTopic, Delivery::kStream, kReadyDepth);
}

ChannelServerLink::~ChannelServerLink() = default;

void ChannelServerLink::publish(ChannelFrame frame) {
  frame.station(station_);
  dds_->write(dds_->frame, frame);
}

void ChannelServerLink::publish(ChannelBulkTile tile) {
  tile.station(station_);
  dds_->write(dds_->tile, tile);
}

std::vector<ChannelReady> ChannelServerLink::take_readies() {
  std::vector<ChannelReady> readies;
  dds_->take<ChannelReady>(dds_->ready_in, [&](const ChannelReady& r, const dds::SampleInfo& info) {
    if (info.valid_data && r.station().to_string() == station_) readies.push_back(r);
  });
  return readies;
}

ChannelFeed::ChannelFeed(const std::string& station, const std::string& display, int domain)
    : station_(station), display_(display) {
  if (const std::string why = why_bad_node_name(station); !why.empty())
    throw std::runtime_error("station name '" + station + "': " + why);
  dds_ = std::make_unique<Participant>(domain, "harbour channel " + display + " of " + station);
  dds_->scene_in = dds_->reader(kSceneTopic, Delivery::kLatestKept, 1);
  dds_->frame_in = dds_->reader(kChannelFrameTopic, Delivery::kLatestKept, 1);
  dds_->tile_in = dds_->reader(kChannelTileTopic, Delivery::kLatestKept, 1, kMostTiles);
  dds_->ready = dds_->writer(kChannelReadyTopic, Delivery::kStream, kReadyDepth);
}

ChannelFeed::~ChannelFeed() = default;

std::optional<StationScene> ChannelFeed::take_scene() {
  std::optional<StationScene> newest;
  dds_->take<StationScene>(dds_->scene_in, [&](const StationScene& s, const dds::SampleInfo& info) {
    if (info.valid_data && s.station().to_string() == station_) newest = s;
  });
  return newest;
}

bool ChannelFeed::take_frame(ChannelFrame& frame) {
  bool taken = false;
  dds_->take<ChannelFrame>(dds_->frame_in, [&](const ChannelFrame& f, const dds::SampleInfo& info) {
    if (info.valid_data && f.station().to_string() == station_) {
      frame = f;
      taken = true;
    }
  });
  return taken;
}

bool ChannelFeed::wait_for_frame(std::chrono::nanoseconds timeout) {
  const std::int64_t ns = std::max<std::int64_t>(timeout.count(), 0);
  return dds_->frame_in->wait_for_unread_message(eprosima::fastrtps::Duration_t(
      static_cast<std::int32_t>(ns / 1000000000), static_cast<std::uint32_t>(ns % 1000000000)));
}

std::vector<ChannelBulkTile> ChannelFeed::take_tiles() {
  std::vector<ChannelBulkTile> tiles;
  dds_->take<ChannelBulkTile>(dds_->tile_in, [&](const ChannelBulkTile& t, const dds::SampleInfo& info) {
    if (info.valid_data && t.station().to_string() == station_) tiles.push_back(t);
  });
  return tiles;
}

void ChannelFeed::ready(ChannelReady ready) {
  ready.station(station_);
  ready.display(display_);
  dds_->write(dds_->ready, ready);
}

void ChannelFeed::leave(std::int64_t attempt, std::chrono::milliseconds timeout) {
  ChannelReady leaving;
  leaving.attempt(attempt);
  leaving.leaving(true);
  ready(std::move(leaving));
  const auto ms = timeout.count();
  dds_->ready->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(
      static_cast<std::int32_t>(ms / 1000), static_cast<std::uint32_t>(ms % 1000) * 1'000'000u));
}

}  // namespace harbour::net
