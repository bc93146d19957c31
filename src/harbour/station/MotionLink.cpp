#include "harbour/station/MotionLink.h"

#include <algorithm>
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

ShortCueSource::ShortCueSource(const scene::SceneDescription& scene) {
  for (std::size_t k = 0; k < scene.drives.size(); ++k)
    if (scene.drives[k] == "engine") engine_ = static_cast<int>(k);
}

motion::ShortCueInputs ShortCueSource::next(const scene::Snapshot& s) {
  motion::ShortCueInputs in;
  if (engine_ >= 0 && engine_ < s.drive_count && !s.power_off) {
    in.engine_speed = s.drives[static_cast<std::size_t>(engine_)].speed;
    in.engine_load = s.drives[static_cast<std::size_t>(engine_)].load;
  }
  // the impacts closed since the last frame (the first frame takes none: they were before it)
  if (knocks_seen_ < 0) knocks_seen_ = s.knocks_total;
  for (std::int64_t k = s.first_knock_after(knocks_seen_); k < s.knocks_total; ++k)
    in.impact_speed_mps = std::max(in.impact_speed_mps, s.knock(k).speed_mps);
  knocks_seen_ = s.knocks_total;
  return in;
}

MotionLink::MotionLink(const io::PlatformFile& platform, const motion::WashoutSettings& washout,
                       const io::DriverSettings& driver, const scene::SceneDescription& scene)
    : motion_(settings_of(platform, washout)),
      short_cues_(scene),
      driver_(platform, driver),
      period_s_(1.0 / washout.rate_hz),
      park_time_s_(platform.sequencer.park_time_s) {}

void MotionLink::update(RealTimeLoop& loop) {
  const std::lock_guard lock(mutex_);
  const double now = now_s();
  if (now < next_s_) return;
  next_s_ += period_s_;
  if (next_s_ < now) next_s_ = now + period_s_;  // fell behind: no burst of frames
  const scene::Snapshot* s = loop.latest_snapshot(kMotionReader);
  if (s && s->step != last_step_) {
    // a frozen simulation sends nothing new: the driver's watchdog fades the platform to neutral
    last_step_ = s->step;
    last_ = motion_.step({s->cab.specific_force_mps2, s->cab.angular_velocity_radps}, short_cues_.next(*s));
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
