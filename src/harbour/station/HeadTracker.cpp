#include "harbour/station/HeadTracker.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace harbour::station {

bool head_pose_from_opentrack(std::span<const std::uint8_t> datagram, const HeadLimits& limits,
                              core::Vec3& offset_m, core::Vec3& yaw_pitch_roll_rad) {
  if (datagram.size() != 6 * sizeof(double)) return false;
  double v[6];
  for (int k = 0; k < 6; ++k) {
    std::uint64_t bits = 0;
    for (int b = 7; b >= 0; --b)
      bits = bits << 8 | datagram[static_cast<std::size_t>(8 * k + b)];
    std::memcpy(&v[k], &bits, sizeof bits);  // little-endian on the wire, whatever this machine is
    if (!std::isfinite(v[k])) return false;
  }
  const double m = limits.max_offset_m, deg = std::numbers::pi / 180.0;
  // OpenTrack x right, y up, z towards the screen (cm) -> cab x forward, y left, z up (m)
  offset_m = {std::clamp(v[2] / 100.0, -m, m), std::clamp(-v[0] / 100.0, -m, m),
              std::clamp(v[1] / 100.0, -m, m)};
  yaw_pitch_roll_rad = {std::clamp(v[3] * deg, -limits.max_yaw_rad, limits.max_yaw_rad),
                        std::clamp(v[4] * deg, -limits.max_pitch_rad, limits.max_pitch_rad),
                        std::clamp(v[5] * deg, -limits.max_roll_rad, limits.max_roll_rad)};
  return true;
}

HeadTracker::HeadTracker(std::uint16_t port, const HeadLimits& limits, bool any_interface) : limits_(limits) {
  socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (socket_ < 0)
    throw std::runtime_error(std::string("head tracking: no UDP socket: ") + std::strerror(errno));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(any_interface ? INADDR_ANY : INADDR_LOOPBACK);
  if (::bind(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    const std::string why = std::strerror(errno);
    ::close(socket_);
    throw std::runtime_error("head tracking: cannot listen on UDP port " + std::to_string(port) + ": " + why);
  }
  socklen_t size = sizeof address;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &size);
  port_ = ntohs(address.sin_port);
  timeval timeout{0, 100000};  // wake to see whether to stop
  ::setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  thread_ = std::thread([this] { receive(); });
}

HeadTracker::~HeadTracker() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  ::close(socket_);
}

void HeadTracker::receive() {
  std::uint8_t buffer[512];
  while (running_.load()) {
    const ssize_t n = ::recv(socket_, buffer, sizeof buffer, 0);
    if (n < 0) continue;  // timeout (or an interrupted call): look at running_ again
    core::Vec3 offset, angles;
    if (!head_pose_from_opentrack({buffer, static_cast<std::size_t>(n)}, limits_, offset, angles)) {
      ++refused_;
      continue;
    }
    {
      const std::lock_guard lock(mutex_);
      offset_m_ = offset;
      angles_rad_ = angles;
      has_pose_ = true;
    }
    ++received_;
  }
}

bool HeadTracker::latest(core::Vec3& offset_m, core::Vec3& yaw_pitch_roll_rad) const {
  const std::lock_guard lock(mutex_);
  offset_m = offset_m_;
  yaw_pitch_roll_rad = angles_rad_;
  return has_pose_;
}

}  // namespace harbour::station
