#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "harbour/io/MotionFiles.h"
#include "harbour/motion/PlatformSequencer.h"
#include "harbour/motion/StewartPlatform.h"

namespace harbour::io {

/// What one platform update says, whatever the wire format.
struct PlatformPacket {
  motion::PlatformState state = motion::PlatformState::kParked;
  bool watchdog_fading = false;  ///< the simulation stopped sending; returning to neutral
  std::uint32_t sequence = 0;
  double time_s = 0.0;  ///< [s] driver clock
  motion::PlatformPose pose;
  motion::ActuatorLengths lengths{};
};

/// harboursim generic packet (docs/models/motion.md): 68 bytes, little-endian, magic "HSMP", version 1.
inline constexpr std::size_t kGenericPacketSize = 68;
std::vector<std::uint8_t> encode_generic(const PlatformPacket& packet);
/// Decodes a generic packet; nullopt for a wrong size, magic, version or state.
std::optional<PlatformPacket> decode_generic(std::span<const std::uint8_t> bytes);

/// Moog 6DOF2000E-style DOF-mode command (as documented by public open-source drivers; not verified on
/// hardware): 32 bytes big-endian, motion command word, then roll, pitch, heave, surge, yaw, lateral as
/// float32 in aerospace axes (x forward, y right, z down), then a reserved word. Default port 991.
inline constexpr std::size_t kMoogPacketSize = 32;
enum MoogCommandWord : std::uint32_t {
  kMoogNewPosition = 130,
  kMoogDofMode = 170,
  kMoogEngage = 180,
  kMoogPark = 210
};
std::array<std::uint8_t, kMoogPacketSize> encode_moog_dof(const PlatformPacket& packet);

/// A connected UDP socket sending datagrams to one host and port (IPv4 literal or name).
class UdpSender {
 public:
  UdpSender(const std::string& host, std::uint16_t port);
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;
  /// Sends one datagram; returns false (never throws) if the kernel refused it.
  bool send(std::span<const std::uint8_t> bytes);

 private:
  int socket_ = -1;
};

enum class PacketFormat { kGeneric, kMoogDof };

/// Where and how the driver talks to the platform.
struct DriverSettings {
  PacketFormat format = PacketFormat::kGeneric;
  std::string host = "127.0.0.1";
  std::uint16_t port = 7701;
};

/// Platform side of the motion system: holds the latest pose from the simulation, runs the engage/park and
/// watchdog sequencer, and sends one packet per tick.
class PlatformDriver {
 public:
  PlatformDriver(const PlatformFile& platform, const DriverSettings& settings);

  /// A new pose from the simulation at driver time `now_s`.
  void submit(const motion::PlatformPose& pose, double now_s);
  void engage() { sequencer_.engage(); }
  void park() { sequencer_.park(); }
  /// Advances the sequencer to `now_s` and sends one packet; returns what was sent.
  PlatformPacket tick(double now_s);

  motion::PlatformState state() const { return sequencer_.state(); }

 private:
  DriverSettings settings_;
  motion::StewartPlatform platform_;
  motion::PlatformSequencer sequencer_;
  UdpSender sender_;
  motion::PlatformPose command_;
  double command_time_s_ = -1e30;
  double last_tick_s_ = 0.0;
  bool ticked_ = false;
  std::uint32_t sequence_ = 0;
};

}  // namespace harbour::io
