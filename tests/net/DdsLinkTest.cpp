// The stations' and the console's DDS link: two participants in one process on a domain of their own.
#include "harbour/net/DdsLink.h"

#include <gtest/gtest.h>

#include <functional>
#include <thread>

namespace harbour::net {
namespace {

constexpr int kDomain = 171;  // tests on the network take their own domains (ctest runs them side by side)

// polls until `done` or 5 s
bool wait_for(ConsoleLink& console, const std::function<bool()>& done) {
  for (int n = 0; n < 500; ++n) {
    console.poll();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(DdsLink, AStationIsSeenCommandedAndAnswersAndIsLostWhenItFallsSilent) {
  ConsoleLink console("console-a", kDomain);
  auto station = std::make_unique<StationLink>("cabin-1", kDomain);
  StationStatus status;
  status.state("running");
  status.exercise("sts_discharge");
  status.time_s(12.5);
  station->publish(status);
  ASSERT_TRUE(wait_for(console, [&] { return console.stations().count("cabin-1") == 1; }));
  const ConsoleLink::Station& seen = console.stations().at("cabin-1");
  EXPECT_EQ(seen.status.state().to_string(), "running");
  EXPECT_EQ(seen.status.exercise().to_string(), "sts_discharge");
  EXPECT_DOUBLE_EQ(seen.status.time_s(), 12.5);
  EXPECT_FALSE(seen.lost);

  // a command reaches the station it names only, and its acknowledgement the console that sent it
  StationLink other("cabin-2", kDomain);
  StationCommand hold;
  hold.station("cabin-1");
  hold.kind("hold");
  hold.user("anna");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // discovery of the command readers
  const std::uint64_t id = console.send(hold);
  std::vector<StationCommand> got;
  for (int n = 0; n < 500 && got.empty(); ++n) {
    got = station->take_commands();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].kind().to_string(), "hold");
  EXPECT_EQ(got[0].user().to_string(), "anna");
  EXPECT_EQ(got[0].console().to_string(), "console-a");
  EXPECT_EQ(got[0].id(), id);
  EXPECT_TRUE(other.take_commands().empty());
  station->acknowledge(got[0], false, "nothing runs to hold");
  std::optional<CommandAck> ack;
  ASSERT_TRUE(wait_for(console, [&] { return (ack = console.take_ack(id)).has_value(); }));
  EXPECT_FALSE(ack->ok());
  EXPECT_EQ(ack->message().to_string(), "nothing runs to hold");

  // events arrive in order, none dropped in a burst
  for (int n = 0; n < 100; ++n) {
    StationEvent e;
    e.kind("collision");
    e.value(n);
    station->publish(e);
  }
  std::vector<StationEvent> events;
  ASSERT_TRUE(wait_for(console, [&] {
    for (StationEvent& e : console.take_events())
      events.push_back(e);
    return events.size() >= 100;
  }));
  ASSERT_EQ(events.size(), 100u);
  for (int n = 0; n < 100; ++n) {
    EXPECT_EQ(events[static_cast<std::size_t>(n)].value(), n);
    EXPECT_EQ(events[static_cast<std::size_t>(n)].sequence_number(), static_cast<std::uint64_t>(n + 1));
  }

  // silent for longer than kLostAfter_s: lost; its link closed in order: gone
  console.poll();
  const auto later =
      ConsoleLink::Clock::now() + std::chrono::milliseconds(static_cast<int>(kLostAfter_s * 1e3) + 500);
  const std::vector<std::string> changed = console.poll(later);
  EXPECT_TRUE(console.stations().at("cabin-1").lost);
  EXPECT_NE(std::find(changed.begin(), changed.end(), "cabin-1"), changed.end());
  station.reset();
  EXPECT_TRUE(wait_for(console, [&] { return console.stations().at("cabin-1").gone; }));
}

TEST(DdsLink, ALateConsoleSeesTheStationsStatusAndSceneAtOnceAndTheStateAtItsSize) {
  StationLink station("rtg-3", kDomain + 1);
  StationStatus status;
  status.state("idle");
  station.publish(status);
  StationScene scene;
  scene.machine("sts");
  std::vector<eprosima::fastrtps::fixed_string<48>> names(2200, "container");
  scene.entity_names(names);
  scene.entity_visuals(names);
  scene.entity_half_extents_m(std::vector<float>(6600, 1.0f));
  station.publish(scene);

  ConsoleLink console("console-late", kDomain + 1);
  ASSERT_TRUE(wait_for(console, [&] {
    return console.stations().count("rtg-3") && console.stations().at("rtg-3").scene.has_value();
  }));
  EXPECT_EQ(console.stations().at("rtg-3").status.state().to_string(), "idle");
  EXPECT_EQ(console.stations().at("rtg-3").scene->entity_names().size(), 2200u);

  // a full state (every entity, every rope point): larger than one UDP datagram, fragmented and whole
  StationState state;
  state.entity_poses(std::vector<float>(15400, 2.5f));
  state.rope_points_m(std::vector<float>(3072, -1.0f));
  state.time_s(3.0);
  ASSERT_TRUE(wait_for(console, [&] {
    station.publish(state);
    return console.stations().at("rtg-3").state.has_value();
  }));
  const StationState& got = *console.stations().at("rtg-3").state;
  EXPECT_EQ(got.entity_poses().size(), 15400u);
  EXPECT_EQ(got.entity_poses().back(), 2.5f);
  EXPECT_EQ(got.rope_points_m().size(), 3072u);

  // a full bulk sample (four 64 x 64 grids): fragmented and whole
  StationBulk bulk;
  bulk.samples_x(std::vector<std::uint16_t>(4, 64));
  bulk.samples_y(std::vector<std::uint16_t>(4, 64));
  bulk.sample_m(std::vector<float>(4, 0.4f));
  bulk.grid_poses(std::vector<float>(28, 0.5f));
  bulk.heights_m(std::vector<float>(16384, 4.25f));
  ASSERT_TRUE(wait_for(console, [&] {
    station.publish(bulk);
    return console.stations().at("rtg-3").bulk.has_value();
  }));
  EXPECT_EQ(console.stations().at("rtg-3").bulk->heights_m().size(), 16384u);
  EXPECT_EQ(console.stations().at("rtg-3").bulk->heights_m().back(), 4.25f);
}

TEST(DdsLink, BadNamesAndDomainsAreRefused) {
  EXPECT_THROW(StationLink("", kDomain), std::runtime_error);
  EXPECT_THROW(StationLink("cabin 1", kDomain), std::runtime_error);
  EXPECT_THROW(StationLink(std::string(65, 'a'), kDomain), std::runtime_error);
  EXPECT_THROW(ConsoleLink("c", 233), std::runtime_error);
  EXPECT_THROW(ConsoleLink("c", -1), std::runtime_error);
}

}  // namespace
}  // namespace harbour::net
