#include "harbour/station/Station.h"

#include <chrono>

#include "harbour/station/HeadTracker.h"
#include "harbour/station/MotionLink.h"
#include "harbour/station/ThreadRole.h"

namespace harbour::station {

Station::Station(Session& session) : session_(session) {}

Station::~Station() {
  stop();
  if (input_) session_.loop().stop();  // the loop samples these devices: it stops before they go
}

void Station::use_devices(std::unique_ptr<DeviceInput> input) {
  input_ = std::move(input);
  input_->maintain();  // devices present now are bound before the first step
  DeviceInput* devices = input_.get();
  session_.loop().set_sampler([devices] { return devices->sample(); });
}

void Station::use_head_tracking(std::unique_ptr<HeadTracker> tracker) {
  head_ = std::move(tracker);
}

void Station::use_motion(std::unique_ptr<MotionLink> motion) {
  motion_ = std::move(motion);
}

void Station::start() {
  if (running_.exchange(true)) return;
  if (motion_) motion_->engage();
  thread_ = std::thread([this] {
    take_role(ThreadRole::kMonitor);
    monitor();
  });
}

void Station::stop_monitoring() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

void Station::stop() {
  stop_monitoring();
  if (motion_) motion_->park_and_wait();
}

std::vector<std::string> Station::take_messages() {
  const std::lock_guard lock(messages_mutex_);
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

void Station::monitor() {
  using Clock = std::chrono::steady_clock;
  constexpr auto kDevicePeriod = std::chrono::milliseconds(20);
  Clock::time_point next_devices = Clock::now();
  while (running_.load()) {
    const Clock::time_point now = Clock::now();
    if (input_ && now >= next_devices) {
      next_devices = now + kDevicePeriod;
      input_->maintain();
      session_.loop().set_devices_missing(input_->missing_devices());
      for (const DeviceEvent& e : input_->take_events()) {
        const char* what = e.kind == DeviceEvent::Kind::kConnected ? "connected"
                           : e.kind == DeviceEvent::Kind::kLost    ? "LOST"
                                                                   : "does not fit its mapping";
        const std::lock_guard lock(messages_mutex_);
        messages_.push_back("input device " + e.device + " (" + e.name + ") " + what + ": " + e.detail);
        if (e.kind != DeviceEvent::Kind::kConnected || session_.loop().stats().steps > 0)
          session_.note_event(e.kind == DeviceEvent::Kind::kConnected ? "device_connected"
                              : e.kind == DeviceEvent::Kind::kLost    ? "device_lost"
                                                                      : "device_unfit");
      }
    }
    if (head_) {
      core::Vec3 position, angles;
      if (head_->latest(position, angles)) session_.loop().set_head_offset(position, angles);
    }
    if (motion_) motion_->update(session_.loop());
    // the platform's cues at 2 kHz, a tracked head at 500 Hz; the devices alone need only their 20 ms
    std::this_thread::sleep_for(motion_ ? std::chrono::microseconds(500)
                                : head_ ? std::chrono::microseconds(2000)
                                        : std::chrono::microseconds(kDevicePeriod));
  }
}

}  // namespace harbour::station
