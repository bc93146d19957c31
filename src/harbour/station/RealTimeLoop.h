#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "harbour/scene/BulkView.h"
#include "harbour/sim/Simulation.h"
#include "harbour/station/SpscRing.h"
#include "harbour/station/TripleBuffer.h"

namespace harbour::station {

/// What the step thread hands to whoever records (off the step thread): every step it took, with the
/// controls it stepped with and the instructor commands applied before it, the state hash every second and,
/// when asked for, the whole state now and then, in order.
struct StepRecord {
  enum class Kind : std::uint8_t {
    kStep,        ///< one step with `controls` (the simulation is now at `step`)
    kCommand,     ///< `command` applied before step `step` + 1
    kTeam,        ///< `team` (another station's doing) applied before step `step` + 1
    kCheckpoint,  ///< the state hash at `step`
    kKeyframe,    ///< the whole state at `step` lies in keyframe slot `keyframe_slot` (release it when kept)
  };
  Kind kind = Kind::kStep;
  std::int64_t step = 0;
  scene::Controls controls;
  sim::InstructorCommand command;
  sim::TeamInput team;
  std::uint64_t state_hash = 0;
  int keyframe_slot = -1;
};

/// A request to the running loop from another thread, applied between steps.
struct LoopCommand {
  enum class Kind : std::uint8_t { kHold, kResume, kSingleStep, kInstructor, kTeam, kStop };
  Kind kind = Kind::kHold;
  sim::InstructorCommand instructor;
  sim::TeamInput team;  ///< kTeam: checked again when applied (one the state no longer allows is dropped)
};

/// How the loop keeps (or fails to keep) real time.
struct LoopStats {
  std::int64_t ticks = 0;            ///< 1 ms ticks since the start (held ones included)
  std::int64_t steps = 0;            ///< simulation steps taken
  std::int64_t late_ticks = 0;       ///< ticks that started a whole period or more after their time
  std::int64_t skipped_ticks = 0;    ///< ticks given up when the loop fell too far behind (time lost)
  std::int64_t catch_up_limits = 0;  ///< times it fell more than the catch-up bound behind
  std::int64_t record_waits = 0;     ///< ticks that waited for the recorder (its queue full)
  double longest_tick_s = 0.0;       ///< longest work of one tick (step, publish, hand-off)
  double worst_lateness_s = 0.0;
  double mean_tick_s = 0.0;
  double real_time_factor = 0.0;  ///< simulated time over wall time, while not held
  bool keeping_real_time = true;  ///< false once it has had to give up ticks
};

/// Who reads which snapshot buffer (each its own triple buffer, at its own rate).
enum SnapshotReader : int {
  kImageGeneratorReader = 0,
  kConsoleReader = 1,
  kMotionReader = 2,
  kPictureReader = 3,  ///< the small cab view a served station sends the instructor
  kSoundReader = 4,    ///< the cab's sound
  kTeamReader = 5,     ///< a team session's other members (this machine's bodies, with their velocities)
  kChannelReader = 6,  ///< the remote image-generator channels
  kSnapshotReaders = 7
};

/// The time the loop paces itself by: the steady clock, or a test's manual clock (real time tested by its
/// mechanism, not by the host's speed).
class LoopClock {
 public:
  using time_point = std::chrono::steady_clock::time_point;
  virtual ~LoopClock() = default;
  virtual time_point now() = 0;
  virtual void sleep_until(time_point at) = 0;
};

struct LoopSettings {
  double max_catch_up_s = 0.05;  ///< behind by more than this, the loop gives the time up instead of racing
  double time_scale = 1.0;       ///< simulated seconds per wall second (an instructor's fast-forward; tests)
  /// Ticks run back to back per wake-up: 1 (a person in the loop: a device's change reaches the next step);
  /// more where nobody feels a millisecond (the autopilot with no window or platform), saving a wake-up a
  /// tick.
  int ticks_per_wake = 1;
  /// Each reader's publish period in steps (SnapshotReader order): the image generator at 250 Hz (it
  /// interpolates by step and time), the console at 50 Hz, the motion platform at 200 Hz (washout at 100 Hz),
  /// the instructor's picture at 20 Hz, the sound at 100 Hz (a 10 ms block each), a team at 50 Hz, remote
  /// image-generator channels at 250 Hz; 0: a reader that is not there (no window, no platform, no team),
  /// given only the first snapshot.
  std::array<int, kSnapshotReaders> snapshot_every_steps{4, 20, 5, 50, 10, 20, 4};
  /// The bulk material's heights for the image generator (tiles changed since copied): 20 Hz, as it flows.
  int bulk_every_steps = 50;
  std::size_t record_capacity = 1 << 15;       ///< steps of hand-off to the recorder (32 s)
  std::int64_t checkpoint_every_steps = 1000;  ///< the state hash handed on (sim::Recorder::kCheckpointEvery)
  /// The whole state handed on every so many steps (sim::Recorder::kKeyframeEvery for a recording); 0: never.
  std::int64_t keyframe_every_steps = 0;
  /// The clock the loop paces itself by (not owned; it outlives the loop); nullptr: the steady clock.
  LoopClock* clock = nullptr;
};

/// The station's real-time loop: the simulation at its fixed 1 kHz step on its own thread, paced to the wall
/// clock. Each tick it applies queued commands, latches the controls (the newest from the input side, or
/// from `pilot`), steps, hands the step to the recorder's queue and publishes a snapshot. It never spirals:
/// behind by more than max_catch_up_s it gives the time up and reports that it cannot keep real time.
class RealTimeLoop {
 public:
  /// Controls decided on the step thread from the simulation (an autopilot); empty: the input side's.
  using Pilot = std::function<scene::Controls(const sim::Simulation&)>;
  /// Asked after every tick on the step thread: true stops the loop (the exercise is over).
  using StopWhen = std::function<bool(const sim::Simulation&)>;
  /// Called on the step thread right after every step with the controls that drove it (the evaluation).
  using StepObserver = std::function<void(const sim::Simulation&, const scene::Controls&)>;

  RealTimeLoop(sim::Simulation& simulation, const LoopSettings& settings = {});
  ~RealTimeLoop();
  RealTimeLoop(const RealTimeLoop&) = delete;
  RealTimeLoop& operator=(const RealTimeLoop&) = delete;

  void set_pilot(Pilot pilot) { pilot_ = std::move(pilot); }
  /// Controls read on the step thread right before each step (the input devices' sample(): a device change
  /// reaches the very next step); with neither a pilot nor a sampler the controls stay neutral.
  void set_sampler(std::function<scene::Controls()> sampler) { sampler_ = std::move(sampler); }
  /// How many input devices are missing now (any thread): published in every snapshot for the displays.
  void set_devices_missing(int count) { devices_missing_ = count; }
  void set_stop_when(StopWhen stop_when) { stop_when_ = std::move(stop_when); }
  void set_observer(StepObserver observer) { observer_ = std::move(observer); }
  /// The eye point's offset from head tracking, written into every published snapshot (any thread).
  void set_head_offset(const core::Vec3& position_m, const core::Vec3& yaw_pitch_roll_rad);
  /// The trainee looking round (keys, a mouse drag): written into every published snapshot (any thread).
  void set_look(double yaw_rad, double pitch_rad);
  /// Adds to the snapshots of `readers` (a bit per SnapshotReader) after the simulation has written them (a
  /// team's other machines, for the readers that draw), on the step thread; set before start() (every reader
  /// is given the start again).
  void set_addition(std::function<void(scene::Snapshot&)> addition, unsigned readers);

  /// Starts the step thread.
  void start();
  /// `ticks` ticks now on the calling thread, unpaced (benchmarks, tools); not while the thread runs.
  void run_ticks(int ticks) {
    for (int n = 0; n < ticks; ++n)
      tick();
  }
  /// Asks the loop to stop after the current tick and waits for it.
  void stop();
  /// Waits until the loop has stopped (by stop(), a kStop command, stop_when or divergence).
  void join();
  bool running() const { return running_.load(); }

  /// Any thread: a command for the loop, applied before the next step. An instructor command out of range
  /// is refused here (false, with why); so is one when the queue is full.
  bool post(const LoopCommand& command, std::string* why = nullptr);

  /// Reader `n`'s newest snapshot (nullptr before the first).
  const scene::Snapshot* latest_snapshot(int reader) {
    return snapshots_[static_cast<std::size_t>(reader)]->latest();
  }
  /// Reader `n`'s newest view of the bulk material (the image generator's or the console's; nullptr in an
  /// exercise without any).
  const scene::BulkView* latest_bulk(int reader) {
    return simulation_.bulk() ? bulk_[static_cast<std::size_t>(reader)].latest() : nullptr;
  }
  /// The recorder's side of the step hand-off (one consumer thread).
  SpscRing<StepRecord>& records() { return records_; }
  /// A kKeyframe record's state (the recorder's thread, until it releases the slot).
  const std::vector<std::uint8_t>& keyframe(int slot) const {
    return keyframes_[static_cast<std::size_t>(slot)].state;
  }
  /// The recorder has kept the slot's state: the step thread may fill it again.
  void release_keyframe(int slot) {
    keyframes_[static_cast<std::size_t>(slot)].full.store(false, std::memory_order_release);
  }
  LoopStats stats() const;
  /// The controls the last step used (step thread's copy; read when stopped).
  const scene::Controls& last_controls() const { return latched_; }

 private:
  void run();
  void tick();
  void apply_commands();
  void step_once();
  void hand_off(const StepRecord& record);
  void hand_off_keyframe();
  /// Waits, counted in record_waits, while the recorder is behind.
  template <typename Ready>
  void wait_for_recorder(Ready ready);
  void publish(int reader);
  void publish_bulk();

  sim::Simulation& simulation_;
  LoopSettings settings_;
  Pilot pilot_;
  std::function<scene::Controls()> sampler_;
  std::atomic<int> devices_missing_{0};
  StopWhen stop_when_;
  StepObserver observer_;
  std::function<void(scene::Snapshot&)> addition_;
  unsigned addition_readers_ = 0;
  std::thread thread_;
  std::atomic<bool> running_{false}, stop_requested_{false};

  scene::Controls latched_;
  std::vector<std::unique_ptr<TripleBuffer<scene::Snapshot>>> snapshots_;
  // by reader (the motion platform's unused); each buffer keeps its own tile versions: copies what changed
  std::array<TripleBuffer<scene::BulkView>, kSnapshotReaders> bulk_;
  SpscRing<StepRecord> records_;
  // two keyframe buffers: the step thread fills one while the recorder may still be writing the other
  struct KeyframeSlot {
    std::vector<std::uint8_t> state;
    std::atomic<bool> full{false};
  };
  std::array<KeyframeSlot, 2> keyframes_;

  std::mutex commands_mutex_;
  std::array<LoopCommand, 256> commands_{};
  std::size_t command_count_ = 0;
  std::array<LoopCommand, 256> applying_{};  // step thread's copy

  std::mutex head_mutex_;
  core::Vec3 head_position_m_, head_angles_rad_;
  double look_yaw_rad_ = 0.0, look_pitch_rad_ = 0.0;

  mutable std::mutex stats_mutex_;
  LoopStats stats_;
  double busy_s_ = 0.0;
};

}  // namespace harbour::station
