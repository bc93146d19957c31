#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harbour/sim/Simulation.h"

namespace harbour::sim {

/// A run as the inputs that drove it, the instructor's commands, the state hash at every recorded second and
/// the whole state every ten seconds (keyframes): replay is re-simulation, from the start or from the
/// keyframe before a moment.
struct Recording {
  struct InputChange {
    std::int64_t step = 0;     ///< the controls take effect from this step on
    scene::Controls controls;  ///< values by control_labels (slot n: control_labels[n])
  };
  struct Checkpoint {
    std::int64_t step = 0;
    std::uint64_t state_hash = 0;
  };
  std::string scenario;          ///< scenario name the run started from
  std::string parent;            ///< recording this one branched from (take-over), empty if none
  std::int64_t branch_step = 0;  ///< step of the parent where the branch starts
  std::int64_t total_steps = 0;
  /// The run started with its hoist ropes stretched under their load (false: unstretched, as runs recorded
  /// before version 8 started; ScenarioSettings::ropes_start_unstretched). A replay starts as the run did.
  bool ropes_settled = true;
  /// The run's ropes stretched along their curved length (false: along their chords, as every run recorded
  /// without header flag bit 1; ScenarioSettings::ropes_stretch_along_chord).
  bool ropes_curved = true;
  /// The reach stacker's telescope end stops lay beyond its drive's travel (false: at it, as in every run
  /// recorded without header flag bit 2; ScenarioSettings::end_stops_at_travel).
  bool end_stops_clear = true;
  /// The run's machine was brought to rest before its first step (false: it started as built, as in
  /// every run recorded without header flag bit 3; ScenarioSettings::start_unsettled).
  bool start_settled = true;
  /// The ropes' transverse damping acted between each rope and its ends (false: against the ground, as in
  /// every run recorded without header flag bit 4; ScenarioSettings::rope_damping_against_ground).
  bool rope_damping_internal = true;
  /// The ropes lost to bending hysteresis where they turned on their sheaves and drums (false: none, as in
  /// every run recorded without header flag bit 5; ScenarioSettings::sheaves_without_bending_loss).
  bool sheave_bending_loss = true;
  /// Its sheaves turned by the change of their rope's transfer, the rope lost to bending running over them,
  /// its strain rate counted the rope transferred and a rope was overloaded after 10 ms above its working
  /// load (false: none of these, as in every run recorded without header flag bit 7;
  /// ScenarioSettings::simple_sheaves).
  bool running_sheaves = true;
  /// A slack rope kept the shape it had (false: it straightened to its chord, as in every run recorded
  /// without header flag bit 8; ScenarioSettings::slack_ropes_straighten).
  bool slack_ropes_keep_sag = true;
  /// Its checkpoints hash everything the machine saves (false: the machine's hand-picked figures, as in
  /// every run recorded without header flag bit 6; ScenarioSettings::machine_hashed_by_hand).
  bool machine_state_hashed = true;
  /// The labels of the controls the values are stored by (a replay reads them by label, whatever slots the
  /// machine's table gives them now).
  std::vector<std::string> control_labels;
  std::vector<InputChange> inputs;      ///< in step order
  std::vector<Checkpoint> checkpoints;  ///< in step order
  struct Command {
    std::int64_t step = 0;  ///< applied before this step
    InstructorCommand command;
  };
  std::vector<Command> commands;  ///< in step order
  struct TeamEvent {
    std::int64_t step = 0;  ///< applied before this step (after its instructor's commands)
    TeamInput input;
  };
  std::vector<TeamEvent> team;  ///< in step order: what the team session's other stations made happen
  struct Keyframe {
    std::int64_t step = 0;
    std::vector<std::uint8_t> state;  ///< Simulation::save_state()
  };
  std::vector<Keyframe> keyframes;  ///< in step order
  /// false for the prefix a crashed or killed run left: it replays up to its last checkpoint (total_steps)
  bool complete = true;
};

/// Where a Recorder streams what it records, as it records it (a file that a crash leaves replayable).
class RecordingSink {
 public:
  virtual ~RecordingSink() = default;
  virtual void on_input(const Recording::InputChange& change) = 0;
  virtual void on_checkpoint(const Recording::Checkpoint& checkpoint) = 0;
  virtual void on_keyframe(const Recording::Keyframe& keyframe) = 0;
  virtual void on_command(const Recording::Command& command) = 0;
  virtual void on_team(const Recording::TeamEvent& event) = 0;
};

/// Records while a simulation runs: call after each step.
class Recorder {
 public:
  static constexpr std::int64_t kCheckpointEvery = 1000;  ///< one simulated second at 1 kHz
  static constexpr std::int64_t kKeyframeEvery = 10000;   ///< ten simulated seconds

  Recorder(std::string scenario, const scene::ControlTable& controls);
  /// Continues an existing recording's prefix (a take-over branch).
  explicit Recorder(Recording prefix) : recording_(std::move(prefix)) {}

  /// `controls` were used for the step that just ended (now at `simulation.steps()`).
  void after_step(const Simulation& simulation, const scene::Controls& controls);
  /// The instructor's command, just applied to `simulation` (before its next step).
  void on_command(const Simulation& simulation, const InstructorCommand& command);

  // The same, from what a simulation stepped elsewhere handed on (a station's step thread to its record
  // keeper): after_step(simulation, ...) is after_step(step, ...), then a checkpoint every kCheckpointEvery
  // steps and a keyframe every kKeyframeEvery.
  /// `controls`, as the machine read them (ControlTable::in_range), drove the step that ended at `step`.
  void after_step(std::int64_t step, const scene::Controls& controls);
  void checkpoint(std::int64_t step, std::uint64_t state_hash);
  void keyframe(std::int64_t step, std::vector<std::uint8_t> state);
  /// A command applied before step `step` + 1.
  void on_command(std::int64_t step, const InstructorCommand& command);
  /// A team input applied before step `step` + 1.
  void on_team(std::int64_t step, const TeamInput& input);
  const Recording& recording() const { return recording_; }
  /// Streams everything recorded from now on to `sink` as well (nullptr: none).
  void set_sink(RecordingSink* sink) { sink_ = sink; }

 private:
  Recording recording_;
  RecordingSink* sink_ = nullptr;
};

/// Outcome of a replay.
struct ReplayResult {
  std::unique_ptr<Simulation> simulation;  ///< the state at the stop step
  int checkpoints_checked = 0;
  int keyframes_used = 0;                      ///< 1 when the replay started from a keyframe
  std::optional<std::int64_t> first_mismatch;  ///< step of the first checkpoint whose hash differed
};

/// Called after every replayed step with the controls of that step (an evaluator watching the replay).
using ReplayObserver = std::function<void(const Simulation&, const scene::Controls&)>;

/// The STS labels recordings before version 7 stored their controls as (in this order).
std::vector<std::string> legacy_sts_control_labels();

class BySlot;

/// Plays a recording back step by step (the console's replay): seek to any step (from the keyframe at or
/// before it, or on from where it is when that is nearer), then advance as fast as wanted; every checkpoint
/// passed is compared. Keeps a reference to `recording` (it must outlive it) and a copy of `scenario`.
class ReplayPlayer {
 public:
  ReplayPlayer(const ScenarioSettings& scenario, const Recording& recording);
  ~ReplayPlayer();
  void seek(std::int64_t step);
  /// Re-simulates on to `step` (at most the recording's end).
  void advance_to(std::int64_t step, const ReplayObserver& observer = {});
  const Simulation& simulation() const { return *simulation_; }
  std::int64_t total_steps() const { return recording_.total_steps; }
  int checkpoints_checked() const { return checkpoints_checked_; }
  int keyframes_used() const { return keyframes_used_; }
  std::optional<std::int64_t> first_mismatch() const { return first_mismatch_; }
  std::unique_ptr<Simulation> release_simulation() { return std::move(simulation_); }

 private:
  ScenarioSettings scenario_;  // started as the recording's run was
  const Recording& recording_;
  std::unique_ptr<Simulation> simulation_;
  std::unique_ptr<BySlot> by_slot_;
  scene::Controls current_;
  std::size_t next_input_ = 0, next_checkpoint_ = 0, next_command_ = 0, next_team_ = 0;
  int checkpoints_checked_ = 0, keyframes_used_ = 0;
  std::optional<std::int64_t> first_mismatch_;
};

/// The name of the box last handed onto this station's trailer at or before `step` (its team inputs' kLoadOn
/// item; "" before any, and in a recording older than version 11): what its "load" entity is drawn as then.
std::string handed_load_name(const Recording& recording, std::int64_t step);

/// Re-simulates `recording` from `scenario` up to `stop_step` (default: its end), comparing every checkpoint.
/// Given a stop step and no observer it starts from the last keyframe at or before it (a seek); a whole
/// replay, or one with an observer, runs every step from the start.
ReplayResult replay(const ScenarioSettings& scenario, const Recording& recording, std::int64_t stop_step = -1,
                    const ReplayObserver& observer = {});

/// Instructor take-over at `step` of a recording: the simulation restored there (from the keyframe before it,
/// then re-simulation; from the start when an observer, e.g. the branch's evaluator, must see the history)
/// and a recorder for the new branch, linked to the original as its parent.
struct TakeOver {
  std::unique_ptr<Simulation> simulation;
  Recorder recorder;
  scene::Controls levers;  ///< the controls standing at the take-over (neutral where none were recorded)
};
TakeOver take_over(const ScenarioSettings& scenario, const Recording& recording,
                   const std::string& recording_id, std::int64_t step, const ReplayObserver& observer = {});

}  // namespace harbour::sim
