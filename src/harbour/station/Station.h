#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "harbour/station/DeviceInput.h"
#include "harbour/station/Session.h"

namespace harbour::station {

class HeadTracker;
class MotionLink;

/// The station around a running session: input devices sampled right before each step and hot-plugged at
/// 50 Hz, head tracking moving the eye point, the motion platform fed from the cab's cues; what happens to
/// the devices goes to the trainee's display (messages, the snapshot's missing-device count) and the
/// attempt's records.
class Station {
 public:
  explicit Station(Session& session);
  ~Station();

  /// Controls come from these devices (replacing any pilot).
  void use_devices(std::unique_ptr<DeviceInput> input);
  void use_head_tracking(std::unique_ptr<HeadTracker> tracker);
  void use_motion(std::unique_ptr<MotionLink> motion);
  /// Starts the monitor thread (devices, head, motion); the session itself is started by its owner.
  void start();
  /// Stops the monitor thread: devices, head and platform are no longer read or fed.
  void stop_monitoring();
  /// stop_monitoring(), then the platform parked (it takes its park time: finish the session first, so that
  /// the simulation does not run on while the platform settles).
  void stop();
  /// Lines for the trainee's display since the last call ("right stick lost: hoist, lock ... safe").
  std::vector<std::string> take_messages();
  DeviceInput* devices() { return input_.get(); }
  HeadTracker* head_tracker() { return head_.get(); }
  MotionLink* motion() { return motion_.get(); }

 private:
  void monitor();

  Session& session_;
  std::unique_ptr<DeviceInput> input_;
  std::unique_ptr<HeadTracker> head_;
  std::unique_ptr<MotionLink> motion_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::mutex messages_mutex_;
  std::vector<std::string> messages_;
};

}  // namespace harbour::station
