#include "harbour/io/PlatformLink.h"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <vector>

namespace harbour::io {
namespace {

using motion::PlatformState;

// a UDP socket on an ephemeral loopback port, standing in for the platform's controller
class Receiver {
 public:
  Receiver() {
    socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(socket_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t n = sizeof a;
    ::getsockname(socket_, reinterpret_cast<sockaddr*>(&a), &n);
    port_ = ntohs(a.sin_port);
  }
  ~Receiver() { ::close(socket_); }
  std::uint16_t port() const { return port_; }
  std::vector<std::uint8_t> receive() {
    pollfd p{socket_, POLLIN, 0};
    if (::poll(&p, 1, 1000) != 1) return {};
    std::vector<std::uint8_t> buffer(512);
    const ssize_t n = ::recv(socket_, buffer.data(), buffer.size(), 0);
    buffer.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    return buffer;
  }

 private:
  int socket_ = -1;
  std::uint16_t port_ = 0;
};

PlatformFile platform() {
  return load_platform(HARBOUR_DATA_DIR "/motion/platform.yaml");
}

TEST(PlatformLink, GenericPacketRoundTripsAndRejectsGarbage) {
  PlatformPacket p;
  p.state = PlatformState::kFading;
  p.watchdog_fading = true;
  p.sequence = 77;
  p.time_s = 12.5;
  p.pose[motion::kPitch] = -0.1;
  p.lengths[3] = 1.2;
  const auto bytes = encode_generic(p);
  ASSERT_EQ(bytes.size(), kGenericPacketSize);
  const auto back = decode_generic(bytes);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->state, PlatformState::kFading);
  EXPECT_TRUE(back->watchdog_fading);
  EXPECT_EQ(back->sequence, 77u);
  EXPECT_EQ(back->time_s, 12.5);
  EXPECT_FLOAT_EQ(static_cast<float>(back->pose[motion::kPitch]), -0.1f);
  EXPECT_FLOAT_EQ(static_cast<float>(back->lengths[3]), 1.2f);
  auto bad = bytes;
  bad[0] ^= 0xFF;
  EXPECT_FALSE(decode_generic(bad).has_value());
  EXPECT_FALSE(decode_generic(std::span(bytes).first(40)).has_value());
}

TEST(PlatformLink, MoogPacketIsBigEndianInAerospaceAxes) {
  PlatformPacket p;
  p.state = PlatformState::kEngaged;
  p.pose[motion::kHeave] = 0.1;  // up in our axes
  p.pose[motion::kSway] = 0.05;  // left in our axes
  const auto b = encode_moog_dof(p);
  EXPECT_EQ((b[0] << 24) | (b[1] << 16) | (b[2] << 8) | b[3], static_cast<int>(kMoogNewPosition));
  auto be_float = [&](int at) {
    const std::uint32_t u = (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
                            (std::uint32_t{b[at + 2]} << 8) | b[at + 3];
    return std::bit_cast<float>(u);
  };
  EXPECT_FLOAT_EQ(be_float(12), -0.1f);   // heave, z down
  EXPECT_FLOAT_EQ(be_float(24), -0.05f);  // lateral, y right
  p.state = PlatformState::kParking;
  EXPECT_EQ(encode_moog_dof(p)[3], kMoogPark);
}

// Engage, stream poses, go silent (watchdog: slow return to neutral), then park -- all over loopback UDP.
TEST(PlatformLink, DriverEngagesFadesToNeutralWhenTheSimulationStopsAndParks) {
  Receiver rx;
  const PlatformFile file = platform();
  PlatformDriver driver(file, {PacketFormat::kGeneric, "127.0.0.1", rx.port()});
  const double dt = 0.01;
  double t = 0.0;
  auto tick = [&] {
    const PlatformPacket sent = driver.tick(t);
    t += dt;
    const auto bytes = rx.receive();
    const auto got = decode_generic(bytes);
    EXPECT_TRUE(got.has_value()) << "packet lost at t=" << t;
    if (!got) return sent;
    EXPECT_EQ(got->sequence, sent.sequence);
    return *got;
  };

  PlatformPacket p = tick();
  EXPECT_EQ(p.state, PlatformState::kParked);
  EXPECT_NEAR(p.pose[motion::kHeave], file.sequencer.parked_pose[motion::kHeave], 1e-6);
  driver.engage();
  while (t < file.sequencer.engage_time_s + 0.1)
    p = tick();
  for (int i = 0; i < motion::kDofCount; ++i)
    EXPECT_NEAR(p.pose[i], 0.0, 1e-6);  // at neutral

  // 2 s of poses from the simulation: a 0.1 m surge offset
  motion::PlatformPose pose;
  pose[motion::kSurge] = 0.1;
  for (int k = 0; k < 200; ++k) {
    driver.submit(pose, t);
    p = tick();
  }
  EXPECT_NEAR(p.pose[motion::kSurge], 0.1, 1e-6);
  EXPECT_EQ(p.state, PlatformState::kEngaged);

  // silence: after the timeout the watchdog fades to neutral, never faster than the fade speed
  const double silent_from = t;
  double last = p.pose[motion::kSurge], fastest = 0.0;
  while (t < silent_from + 15.0) {
    p = tick();
    if (t - silent_from > file.sequencer.watchdog_timeout_s + 2 * dt) {
      EXPECT_EQ(p.state, PlatformState::kFading);
    }
    EXPECT_LE(p.pose[motion::kSurge], last + 1e-6);  // monotonic return (sub-micrometre rounding)
    fastest = std::max(fastest, (last - p.pose[motion::kSurge]) / dt);
    last = p.pose[motion::kSurge];
  }
  EXPECT_TRUE(p.watchdog_fading);
  EXPECT_LE(fastest, file.sequencer.fade_limits.max_velocity[motion::kSurge] * (1 + 1e-4));
  EXPECT_NEAR(p.pose[motion::kSurge], 0.0, 1e-4);

  driver.park();
  while (t < silent_from + 15.0 + file.sequencer.park_time_s + 0.1)
    p = tick();
  EXPECT_EQ(p.state, PlatformState::kParked);
  EXPECT_NEAR(p.pose[motion::kHeave], file.sequencer.parked_pose[motion::kHeave], 1e-6);
  const motion::StewartPlatform sp(file.geometry);
  EXPECT_TRUE(sp.reachable(p.lengths));
}

TEST(PlatformLink, UnresolvableAddressIsAClearError) {
  EXPECT_THROW(UdpSender("no-such-host.invalid", 991), std::runtime_error);
}

}  // namespace
}  // namespace harbour::io
