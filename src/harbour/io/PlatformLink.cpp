#include "harbour/io/PlatformLink.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace harbour::io {
namespace {

constexpr std::uint32_t kGenericMagic = 0x504D5348;  // "HSMP" as little-endian bytes
constexpr std::uint16_t kGenericVersion = 1;

template <typename T>
void put_le(std::uint8_t* at, T value) {
  auto bits = std::bit_cast<std::array<std::uint8_t, sizeof(T)>>(value);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bits.begin(), bits.end());
  std::memcpy(at, bits.data(), sizeof(T));
}

template <typename T>
T get_le(const std::uint8_t* at) {
  std::array<std::uint8_t, sizeof(T)> bits;
  std::memcpy(bits.data(), at, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bits.begin(), bits.end());
  return std::bit_cast<T>(bits);
}

template <typename T>
void put_be(std::uint8_t* at, T value) {
  auto bits = std::bit_cast<std::array<std::uint8_t, sizeof(T)>>(value);
  if constexpr (std::endian::native == std::endian::little) std::reverse(bits.begin(), bits.end());
  std::memcpy(at, bits.data(), sizeof(T));
}

}  // namespace

std::vector<std::uint8_t> encode_generic(const PlatformPacket& p) {
  std::vector<std::uint8_t> out(kGenericPacketSize, 0);
  put_le(&out[0], kGenericMagic);
  put_le(&out[4], kGenericVersion);
  out[6] = static_cast<std::uint8_t>(p.state);
  out[7] = p.watchdog_fading ? 1 : 0;
  put_le(&out[8], p.sequence);
  put_le(&out[12], p.time_s);
  for (int i = 0; i < 6; ++i)
    put_le(&out[20 + 4 * i], static_cast<float>(p.pose[i]));
  for (int i = 0; i < 6; ++i)
    put_le(&out[44 + 4 * i], static_cast<float>(p.lengths[i]));
  return out;
}

std::optional<PlatformPacket> decode_generic(std::span<const std::uint8_t> b) {
  if (b.size() != kGenericPacketSize || get_le<std::uint32_t>(&b[0]) != kGenericMagic ||
      get_le<std::uint16_t>(&b[4]) != kGenericVersion ||
      b[6] > static_cast<std::uint8_t>(motion::PlatformState::kParking))
    return std::nullopt;
  PlatformPacket p;
  p.state = static_cast<motion::PlatformState>(b[6]);
  p.watchdog_fading = (b[7] & 1) != 0;
  p.sequence = get_le<std::uint32_t>(&b[8]);
  p.time_s = get_le<double>(&b[12]);
  for (int i = 0; i < 6; ++i)
    p.pose[i] = get_le<float>(&b[20 + 4 * i]);
  for (int i = 0; i < 6; ++i)
    p.lengths[i] = get_le<float>(&b[44 + 4 * i]);
  return p;
}

std::array<std::uint8_t, kMoogPacketSize> encode_moog_dof(const PlatformPacket& p) {
  using motion::PlatformState;
  std::uint32_t word = kMoogNewPosition;
  if (p.state == PlatformState::kParked || p.state == PlatformState::kParking) word = kMoogPark;
  if (p.state == PlatformState::kEngaging) word = kMoogEngage;
  // our axes are x forward, y left, z up; the interface's are x forward, y right, z down
  const float values[6] = {
      static_cast<float>(p.pose[motion::kRoll]),   static_cast<float>(-p.pose[motion::kPitch]),
      static_cast<float>(-p.pose[motion::kHeave]), static_cast<float>(p.pose[motion::kSurge]),
      static_cast<float>(-p.pose[motion::kYaw]),   static_cast<float>(-p.pose[motion::kSway])};
  std::array<std::uint8_t, kMoogPacketSize> out{};
  put_be(&out[0], word);
  for (int i = 0; i < 6; ++i)
    put_be(&out[4 + 4 * i], values[i]);
  return out;
}

UdpSender::UdpSender(const std::string& host, std::uint16_t port) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0 || !found)
    throw std::runtime_error("motion platform address " + host + ":" + std::to_string(port) +
                             " cannot be resolved");
  socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  const bool connected = socket_ >= 0 && ::connect(socket_, found->ai_addr, found->ai_addrlen) == 0;
  freeaddrinfo(found);
  if (!connected) {
    if (socket_ >= 0) ::close(socket_);
    throw std::runtime_error("cannot open a UDP socket to " + host + ":" + std::to_string(port));
  }
}

UdpSender::~UdpSender() {
  if (socket_ >= 0) ::close(socket_);
}

bool UdpSender::send(std::span<const std::uint8_t> bytes) {
  return ::send(socket_, bytes.data(), bytes.size(), MSG_DONTWAIT) == static_cast<ssize_t>(bytes.size());
}

PlatformDriver::PlatformDriver(const PlatformFile& platform, const DriverSettings& settings)
    : settings_(settings),
      platform_(platform.geometry),
      sequencer_(platform.sequencer),
      sender_(settings.host, settings.port) {}

void PlatformDriver::submit(const motion::PlatformPose& pose, double now_s) {
  command_ = pose;
  command_time_s_ = now_s;
}

PlatformPacket PlatformDriver::tick(double now_s) {
  const double dt = ticked_ ? now_s - last_tick_s_ : 0.0;
  last_tick_s_ = now_s;
  ticked_ = true;
  PlatformPacket p;
  p.pose = sequencer_.step(dt, command_, now_s - command_time_s_);
  p.state = sequencer_.state();
  p.watchdog_fading = p.state == motion::PlatformState::kFading;
  p.sequence = sequence_++;
  p.time_s = now_s;
  p.lengths = platform_.inverse(p.pose);
  if (settings_.format == PacketFormat::kGeneric) {
    sender_.send(encode_generic(p));
  } else {
    sender_.send(encode_moog_dof(p));
  }
  return p;
}

}  // namespace harbour::io
