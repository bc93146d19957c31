#include "harbour/station/RealTimeLoop.h"

#include <algorithm>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/station/ThreadRole.h"

namespace harbour::station {

namespace {
using Clock = std::chrono::steady_clock;

class SteadyClock final : public LoopClock {
 public:
  time_point now() override { return Clock::now(); }
  void sleep_until(time_point at) override { std::this_thread::sleep_until(at); }
};

LoopClock& steady_clock() {
  static SteadyClock clock;
  return clock;
}
}  // namespace

RealTimeLoop::RealTimeLoop(sim::Simulation& simulation, const LoopSettings& settings)
    : simulation_(simulation), settings_(settings), records_(settings.record_capacity) {
  latched_ = simulation.control_table().neutral();
  for (int n = 0; n < kSnapshotReaders; ++n) {
    snapshots_.push_back(std::make_unique<TripleBuffer<scene::Snapshot>>());
    settings_.snapshot_every_steps[static_cast<std::size_t>(n)] =
        std::max(settings_.snapshot_every_steps[static_cast<std::size_t>(n)], 0);
  }
  settings_.bulk_every_steps = std::max(settings_.bulk_every_steps, 1);
  settings_.ticks_per_wake = std::max(settings_.ticks_per_wake, 1);
  for (int n = 0; n < kSnapshotReaders; ++n)
    publish(n);  // readers see the start
  // every bulk buffer gets its grids and room for the material in flight now, then allocates no more
  if (const bulk::BulkWorld* material = simulation_.bulk())
    for (TripleBuffer<scene::BulkView>& reader : bulk_)
      reader.prepare_each([material](scene::BulkView& view) {
        view.parcels.reserve(bulk::BulkWorld::kParcelsReserved);
        bulk::publish(*material, view);
      });
  publish_bulk();
}

RealTimeLoop::~RealTimeLoop() {
  stop();
}

void RealTimeLoop::set_head_offset(const core::Vec3& position_m, const core::Vec3& yaw_pitch_roll_rad) {
  const std::lock_guard lock(head_mutex_);
  head_position_m_ = position_m;
  head_angles_rad_ = yaw_pitch_roll_rad;
}

void RealTimeLoop::set_look(double yaw_rad, double pitch_rad) {
  const std::lock_guard lock(head_mutex_);
  look_yaw_rad_ = yaw_rad;
  look_pitch_rad_ = pitch_rad;
}

void RealTimeLoop::set_addition(std::function<void(scene::Snapshot&)> addition, unsigned readers) {
  addition_ = std::move(addition);
  addition_readers_ = readers;
  for (int n = 0; n < kSnapshotReaders; ++n)
    publish(n);
}

void RealTimeLoop::start() {
  if (running_.exchange(true)) return;
  stop_requested_ = false;
  thread_ = std::thread([this] { run(); });
}

void RealTimeLoop::stop() {
  stop_requested_ = true;
  join();
}

void RealTimeLoop::join() {
  if (thread_.joinable()) thread_.join();
}

bool RealTimeLoop::post(const LoopCommand& command, std::string* why) {
  if (command.kind == LoopCommand::Kind::kInstructor) {
    // checked here, at the edge: the step thread applies only valid commands
    if (const std::string problem = simulation_.why_refused(command.instructor); !problem.empty()) {
      if (why) *why = problem;
      return false;
    }
  }
  if (command.kind == LoopCommand::Kind::kTeam) {
    if (const std::string problem = sim::why_invalid(command.team); !problem.empty()) {
      if (why) *why = problem;
      return false;
    }
  }
  const std::lock_guard lock(commands_mutex_);
  if (command_count_ == commands_.size()) {
    if (why) *why = "the loop's command queue is full";
    return false;
  }
  commands_[command_count_++] = command;
  return true;
}

LoopStats RealTimeLoop::stats() const {
  const std::lock_guard lock(stats_mutex_);
  return stats_;
}

void RealTimeLoop::run() {
  take_role(ThreadRole::kStep);
  LoopClock& clock = settings_.clock ? *settings_.clock : steady_clock();
  // one tick per simulation step (1 ms), scaled for a fast-forward
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(sim::Simulation::kStep_s / settings_.time_scale));
  const Clock::time_point start = clock.now();
  std::int64_t ticks = 0;  // ticks started (or given up)
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    const Clock::time_point due_at = start + ticks * period;
    Clock::time_point now = clock.now();
    if (now < due_at && ticks % settings_.ticks_per_wake == 0) {
      clock.sleep_until(due_at);
      now = clock.now();
    }
    const auto behind = now - due_at;
    const auto bound =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(settings_.max_catch_up_s));
    if (behind > bound) {
      // too far behind to catch up without a burst the trainee would see: give the time up
      const std::int64_t lost = (behind - bound) / period + 1;
      ticks += lost;
      const std::lock_guard lock(stats_mutex_);
      stats_.skipped_ticks += lost;
      ++stats_.catch_up_limits;
      stats_.keeping_real_time = false;
      continue;
    }
    tick();
    const double work_s = std::chrono::duration<double>(clock.now() - now).count();
    ++ticks;
    {
      const std::lock_guard lock(stats_mutex_);
      stats_.ticks = ticks;
      stats_.steps = simulation_.steps();
      const double late_s = std::chrono::duration<double>(behind).count();
      if (behind >= period) ++stats_.late_ticks;
      stats_.worst_lateness_s = std::max(stats_.worst_lateness_s, late_s);
      stats_.longest_tick_s = std::max(stats_.longest_tick_s, work_s);
      busy_s_ += work_s;
      stats_.mean_tick_s = busy_s_ / static_cast<double>(ticks - stats_.skipped_ticks);
      const double wall_s = std::chrono::duration<double>(clock.now() - start).count();
      stats_.real_time_factor =
          wall_s > 0.0 ? static_cast<double>(ticks - stats_.skipped_ticks) * sim::Simulation::kStep_s / wall_s
                       : 0.0;
    }
    if (simulation_.diverged() || (stop_when_ && stop_when_(simulation_))) break;
  }
  running_ = false;
}

void RealTimeLoop::tick() {
  apply_commands();
  if (!simulation_.held()) step_once();
  for (int n = 0; n < kSnapshotReaders; ++n) {
    const int every = settings_.snapshot_every_steps[static_cast<std::size_t>(n)];
    if (every > 0 && (simulation_.steps() % every == 0 || simulation_.held())) publish(n);
  }
  if (simulation_.steps() % settings_.bulk_every_steps == 0 && !simulation_.held()) publish_bulk();
}

void RealTimeLoop::apply_commands() {
  std::size_t count = 0;
  {
    const std::lock_guard lock(commands_mutex_);
    count = command_count_;
    std::copy_n(commands_.begin(), count, applying_.begin());
    command_count_ = 0;
  }
  for (std::size_t n = 0; n < count; ++n) {
    const LoopCommand& c = applying_[n];
    switch (c.kind) {
      case LoopCommand::Kind::kHold:
        simulation_.hold();
        break;
      case LoopCommand::Kind::kResume:
        simulation_.resume();
        break;
      case LoopCommand::Kind::kSingleStep:
        // not past the end: a step that ended the exercise is its last, even with more queued
        if (simulation_.held() && !(stop_when_ && stop_when_(simulation_))) step_once();
        break;
      case LoopCommand::Kind::kInstructor: {
        simulation_.command(c.instructor);  // valid: post() checked it
        StepRecord r;
        r.kind = StepRecord::Kind::kCommand;
        r.step = simulation_.steps();
        r.command = c.instructor;
        hand_off(r);
        break;
      }
      case LoopCommand::Kind::kTeam: {
        // what this state refuses (a box taken over twice, a second load) is dropped, not recorded
        if (!simulation_.why_refused(c.team).empty()) break;
        simulation_.team_input(c.team);
        StepRecord r;
        r.kind = StepRecord::Kind::kTeam;
        r.step = simulation_.steps();
        r.team = c.team;
        hand_off(r);
        break;
      }
      case LoopCommand::Kind::kStop:
        stop_requested_ = true;
        break;
    }
  }
}

void RealTimeLoop::step_once() {
  if (pilot_)
    latched_ = pilot_(simulation_);
  else if (sampler_)
    latched_ = sampler_();
  simulation_.single_step(latched_);
  if (observer_) observer_(simulation_, latched_);
  StepRecord r;
  r.kind = StepRecord::Kind::kStep;
  r.step = simulation_.steps();
  r.controls = latched_;
  hand_off(r);
  if (settings_.checkpoint_every_steps > 0 && simulation_.steps() % settings_.checkpoint_every_steps == 0) {
    StepRecord c;
    c.kind = StepRecord::Kind::kCheckpoint;
    c.step = simulation_.steps();
    c.state_hash = simulation_.state_hash();
    hand_off(c);
  }
  if (settings_.keyframe_every_steps > 0 && simulation_.steps() % settings_.keyframe_every_steps == 0)
    hand_off_keyframe();
}

template <typename Ready>
void RealTimeLoop::wait_for_recorder(Ready ready) {
  if (ready()) return;
  {
    const std::lock_guard lock(stats_mutex_);
    ++stats_.record_waits;
  }
  // a millisecond at a time: the recorder is far behind, a tick's wait changes nothing; asked to stop (the
  // recorder may have failed), the loop waits no more
  while (!ready() && !stop_requested_.load())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void RealTimeLoop::hand_off(const StepRecord& record) {
  // the recording must be whole: with the recorder's queue full (it fell 32 s behind) the loop waits
  wait_for_recorder([&] { return records_.push(record); });
}

void RealTimeLoop::hand_off_keyframe() {
  // a slot the recorder has released (it keeps a keyframe within ten simulated seconds, or waits)
  int slot = -1;
  wait_for_recorder([&] {
    for (std::size_t k = 0; k < keyframes_.size() && slot < 0; ++k)
      if (!keyframes_[k].full.load(std::memory_order_acquire)) slot = static_cast<int>(k);
    return slot >= 0;
  });
  if (slot < 0) return;  // stopping
  KeyframeSlot& keyframe = keyframes_[static_cast<std::size_t>(slot)];
  keyframe.state = simulation_.save_state();
  keyframe.full.store(true, std::memory_order_release);
  StepRecord k;
  k.kind = StepRecord::Kind::kKeyframe;
  k.step = simulation_.steps();
  k.keyframe_slot = slot;
  hand_off(k);
}

void RealTimeLoop::publish_bulk() {
  const bulk::BulkWorld* material = simulation_.bulk();
  if (!material) return;
  // the readers there are that draw it (the motion platform does not)
  for (int n = 0; n < kSnapshotReaders; ++n) {
    if (n == kMotionReader || settings_.snapshot_every_steps[static_cast<std::size_t>(n)] == 0) continue;
    TripleBuffer<scene::BulkView>& reader = bulk_[static_cast<std::size_t>(n)];
    bulk::publish(*material, reader.back());
    reader.publish();
  }
}

void RealTimeLoop::publish(int reader) {
  core::Vec3 head_position, head_angles;
  double look_yaw = 0.0, look_pitch = 0.0;
  {
    const std::lock_guard lock(head_mutex_);  // uncontended: the station writes it at 500 Hz
    head_position = head_position_m_;
    head_angles = head_angles_rad_;
    look_yaw = look_yaw_rad_;
    look_pitch = look_pitch_rad_;
  }
  TripleBuffer<scene::Snapshot>& buffer = *snapshots_[static_cast<std::size_t>(reader)];
  scene::Snapshot& s = buffer.back();
  simulation_.write_snapshot(s);
  s.cab.head_offset_m = head_position;
  s.cab.head_yaw_pitch_roll_rad = head_angles;
  s.cab.look_yaw_rad = look_yaw;
  s.cab.look_pitch_rad = look_pitch;
  s.devices_missing = devices_missing_.load(std::memory_order_relaxed);
  if (addition_ && (addition_readers_ >> reader & 1u)) addition_(s);
  buffer.publish();
}

}  // namespace harbour::station
