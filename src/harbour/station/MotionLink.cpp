#include "harbour/station/MotionLink.h"

#include <thread>

namespace harbour::station {

namespace {
motion::MotionSettings settings_of(const io::PlatformFile& platform, const motion::WashoutSettings& washout) {
  motion::MotionSettings s;
  s.washout = washout;
  s.geometry = platform.geometry;
  s.limits = platform.limits;
  return s;
}
}  // namespace

MotionLink::MotionLink(const io::PlatformFile& platform, const motion::WashoutSettings& washout,
                       const io::DriverSettings& driver)
    : motion_(settings_of(platform, washout)),
      driver_(platform, driver),
      period_s_(1.0 / washout.rate_hz),
      park_time_s_(platform.sequencer.park_time_s) {}

void MotionLink::update(RealTimeLoop& loop) {
  const std::lock_guard lock(mutex_);
  const double now = now_s();
  if (now < next_s_) return;
  next_s_ += period_s_;
  if (next_s_ < now) next_s_ = now + period_s_;  // fell behind: no burst of frames
  const sim::Snapshot* s = loop.latest_snapshot(kMotionReader);
  if (s && s->step != last_step_) {
    // a frozen simulation sends nothing new: the driver's watchdog fades the platform to neutral
    last_step_ = s->step;
    last_ = motion_.step({s->cab.specific_force_mps2, s->cab.angular_velocity_radps});
    driver_.submit(last_.pose, now);
  }
  driver_.tick(now);
  ++frames_;
}

void MotionLink::park_and_wait() {
  {
    const std::lock_guard lock(mutex_);
    driver_.park();
  }
  const double until = now_s() + park_time_s_ + 0.5;
  while (now_s() < until && state() != motion::PlatformState::kParked) {
    {
      const std::lock_guard lock(mutex_);
      driver_.tick(now_s());
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(period_s_));
  }
}

}  // namespace harbour::station
