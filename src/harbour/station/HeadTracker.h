#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <thread>

#include "harbour/core/Vec3.h"

namespace harbour::station {

/// How far head tracking may move the eye from the design eye point (a seated operator's reach).
struct HeadLimits {
  double max_offset_m = 0.35;   ///< [m] each axis
  double max_yaw_rad = 1.75;    ///< ~100 deg: looking round over a shoulder
  double max_pitch_rad = 1.05;  ///< ~60 deg: down through the cab floor
  double max_roll_rad = 0.6;
};

/// One OpenTrack "UDP over network" datagram: six little-endian doubles x, y, z [cm] and yaw, pitch, roll
/// [deg] (OpenTrack's frame: x right, y up, z towards the screen), to the cab frame (x forward, y left,
/// z up) in metres and radians, clamped to the limits. False for anything but 48 bytes of finite numbers.
bool head_pose_from_opentrack(std::span<const std::uint8_t> datagram, const HeadLimits& limits,
                              core::Vec3& offset_m, core::Vec3& yaw_pitch_roll_rad);

/// Receives OpenTrack's UDP output on a port (loopback or any interface) on a thread of its own; the station
/// reads the newest head pose whenever it publishes a snapshot.
class HeadTracker {
 public:
  /// Binds the port (throws naming it and the error).
  explicit HeadTracker(std::uint16_t port, const HeadLimits& limits = {}, bool any_interface = false);
  ~HeadTracker();
  HeadTracker(const HeadTracker&) = delete;
  HeadTracker& operator=(const HeadTracker&) = delete;

  /// The newest pose; false until the first good datagram.
  bool latest(core::Vec3& offset_m, core::Vec3& yaw_pitch_roll_rad) const;
  long received() const { return received_.load(); }
  long refused() const { return refused_.load(); }
  std::uint16_t port() const { return port_; }

 private:
  void receive();

  HeadLimits limits_;
  int socket_ = -1;
  std::uint16_t port_ = 0;
  std::thread thread_;
  std::atomic<bool> running_{true};
  std::atomic<long> received_{0}, refused_{0};
  mutable std::mutex mutex_;
  bool has_pose_ = false;
  core::Vec3 offset_m_, angles_rad_;
};

}  // namespace harbour::station
