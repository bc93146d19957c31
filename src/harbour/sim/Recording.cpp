#include "harbour/sim/Recording.h"

#include <algorithm>
#include <string>

#include "harbour/core/StateArchive.h"

namespace harbour::sim {

Recorder::Recorder(std::string scenario, const scene::ControlTable& controls) {
  recording_.scenario = std::move(scenario);
  for (const scene::ControlSpec& c : controls.controls())
    recording_.control_labels.push_back(c.label);
}

std::vector<std::string> legacy_sts_control_labels() {
  return {"gantry",      "trolley",        "hoist",     "boom",        "lock",
          "unlock",      "emergency_stop", "horn",      "spreader_20", "spreader_40",
          "spreader_45", "flipper_1",      "flipper_2", "flipper_3",   "flipper_4"};
}

void Recorder::after_step(const Simulation& simulation, const scene::Controls& given) {
  const std::int64_t step = simulation.steps();
  after_step(step, simulation.control_table().in_range(given));
  if (step % kCheckpointEvery == 0) checkpoint(step, simulation.state_hash());
  if (step % kKeyframeEvery == 0) keyframe(step, simulation.save_state());
}

void Recorder::on_command(const Simulation& simulation, const InstructorCommand& command) {
  on_command(simulation.steps(), command);
}

void Recorder::after_step(std::int64_t step, const scene::Controls& controls) {
  // the controls only when they change; the step they were applied at is one before the current
  if (recording_.inputs.empty() || !(recording_.inputs.back().controls == controls)) {
    recording_.inputs.push_back({step - 1, controls});
    if (sink_) sink_->on_input(recording_.inputs.back());
  }
  recording_.total_steps = step;
}

void Recorder::checkpoint(std::int64_t step, std::uint64_t state_hash) {
  recording_.checkpoints.push_back({step, state_hash});
  if (sink_) sink_->on_checkpoint(recording_.checkpoints.back());
}

void Recorder::keyframe(std::int64_t step, std::vector<std::uint8_t> state) {
  recording_.keyframes.push_back({step, std::move(state)});
  if (sink_) sink_->on_keyframe(recording_.keyframes.back());
}

void Recorder::on_command(std::int64_t step, const InstructorCommand& command) {
  recording_.commands.push_back({step, command});
  if (sink_) sink_->on_command(recording_.commands.back());
}

void Recorder::on_team(std::int64_t step, const TeamInput& input) {
  recording_.team.push_back({step, input});
  if (sink_) sink_->on_team(recording_.team.back());
}

// recorded values (by the recording's labels) at this machine's slots
class BySlot {
 public:
  BySlot(const std::vector<std::string>& labels, const scene::ControlTable& table) : table_(table) {
    for (const std::string& label : labels) {
      slot_of_.push_back(table.find(label));
      if (slot_of_.back() < 0)
        throw core::StateError("the recording has a control '" + label + "' this machine does not");
    }
  }
  /// Throws core::StateError at a value the control cannot take (the recorder stores them as read).
  scene::Controls operator()(const scene::Controls& recorded) const {
    scene::Controls c = table_.neutral();
    for (std::size_t n = 0; n < slot_of_.size(); ++n)
      c.value[static_cast<std::size_t>(slot_of_[n])] = recorded.value[n];
    const scene::Controls read = table_.in_range(c);
    for (std::size_t n = 0; n < slot_of_.size(); ++n) {
      const auto slot = static_cast<std::size_t>(slot_of_[n]);
      if (!(read.value[slot] == c.value[slot]))
        throw core::StateError("the recording's control '" + table_[slot_of_[n]].label + "' holds " +
                               std::to_string(c.value[slot]) + ", a value it cannot take");
    }
    return c;
  }

 private:
  const scene::ControlTable& table_;
  std::vector<int> slot_of_;
};

namespace {
ScenarioSettings as_recorded(ScenarioSettings scenario, const Recording& recording) {
  scenario.ropes_start_unstretched = !recording.ropes_settled;
  scenario.ropes_stretch_along_chord = !recording.ropes_curved;
  scenario.end_stops_at_travel = !recording.end_stops_clear;
  scenario.start_unsettled = !recording.start_settled;
  scenario.rope_damping_against_ground = !recording.rope_damping_internal;
  scenario.sheaves_without_bending_loss = !recording.sheave_bending_loss;
  scenario.simple_sheaves = !recording.running_sheaves;
  scenario.slack_ropes_straighten = !recording.slack_ropes_keep_sag;
  scenario.machine_hashed_by_hand = !recording.machine_state_hashed;
  return scenario;
}
}  // namespace

ReplayPlayer::ReplayPlayer(const ScenarioSettings& scenario, const Recording& recording)
    : scenario_(as_recorded(scenario, recording)),
      recording_(recording),
      simulation_(std::make_unique<Simulation>(scenario_)) {
  by_slot_ = std::make_unique<BySlot>(recording.control_labels, simulation_->control_table());
  current_ = simulation_->control_table().neutral();
}

ReplayPlayer::~ReplayPlayer() = default;

void ReplayPlayer::seek(std::int64_t step) {
  const std::int64_t end = std::clamp<std::int64_t>(step, 0, recording_.total_steps);
  const Recording::Keyframe* start = nullptr;
  for (const Recording::Keyframe& k : recording_.keyframes)
    if (k.step <= end) start = &k;
  // forward within the next keyframe's span: on from here; otherwise from the keyframe (or the start)
  const bool onward = simulation_->steps() <= end && (!start || start->step <= simulation_->steps());
  if (!onward) {
    simulation_ = std::make_unique<Simulation>(scenario_);
    by_slot_ =
        std::make_unique<BySlot>(recording_.control_labels, simulation_->control_table());  // its table
    next_input_ = next_checkpoint_ = next_command_ = next_team_ = 0;
    current_ = simulation_->control_table().neutral();
    if (start) {
      simulation_->restore_state(start->state);
      ++keyframes_used_;
      // a keyframe that does not give its second's recorded hash would replay a state that never was
      for (const Recording::Checkpoint& c : recording_.checkpoints)
        if (c.step == start->step && c.state_hash != simulation_->state_hash())
          throw core::StateError("the keyframe at step " + std::to_string(start->step) +
                                 " does not give the state hash recorded there (a damaged recording)");
      // a keyframe holds the commands before its step; those at its step came after it was taken
      while (next_command_ < recording_.commands.size() &&
             recording_.commands[next_command_].step < simulation_->steps())
        ++next_command_;
      while (next_team_ < recording_.team.size() && recording_.team[next_team_].step < simulation_->steps())
        ++next_team_;
    }
  }
  advance_to(end);
}

void ReplayPlayer::advance_to(std::int64_t step, const ReplayObserver& observer) {
  const std::int64_t end = std::min(step, recording_.total_steps);
  Simulation& sim = *simulation_;
  while (sim.steps() < end) {
    while (next_command_ < recording_.commands.size() &&
           recording_.commands[next_command_].step == sim.steps())
      sim.command(recording_.commands[next_command_++].command);
    while (next_team_ < recording_.team.size() && recording_.team[next_team_].step == sim.steps())
      sim.team_input(recording_.team[next_team_++].input);
    while (next_input_ < recording_.inputs.size() && recording_.inputs[next_input_].step <= sim.steps())
      current_ = (*by_slot_)(recording_.inputs[next_input_++].controls);
    sim.single_step(current_);  // replay ignores the freeze: held periods were not recorded as steps
    if (observer) observer(sim, current_);
    while (next_checkpoint_ < recording_.checkpoints.size() &&
           recording_.checkpoints[next_checkpoint_].step < sim.steps())
      ++next_checkpoint_;
    if (next_checkpoint_ < recording_.checkpoints.size() &&
        recording_.checkpoints[next_checkpoint_].step == sim.steps()) {
      ++checkpoints_checked_;
      if (!first_mismatch_ && recording_.checkpoints[next_checkpoint_].state_hash != sim.state_hash())
        first_mismatch_ = sim.steps();
      ++next_checkpoint_;
    }
  }
}

std::string handed_load_name(const Recording& recording, std::int64_t step) {
  std::string name;
  for (const Recording::TeamEvent& e : recording.team) {
    if (e.step > step) break;  // in order (the reader checks)
    if (e.input.kind == TeamInput::Kind::kLoadOn) name = e.input.item_name();
  }
  return name;
}

ReplayResult replay(const ScenarioSettings& scenario, const Recording& recording, std::int64_t stop_step,
                    const ReplayObserver& observer) {
  ReplayPlayer player(scenario, recording);
  if (stop_step >= 0 && !observer)
    player.seek(stop_step);
  else
    player.advance_to(stop_step < 0 ? recording.total_steps : stop_step, observer);
  ReplayResult result;
  result.checkpoints_checked = player.checkpoints_checked();
  result.keyframes_used = player.keyframes_used();
  result.first_mismatch = player.first_mismatch();
  result.simulation = player.release_simulation();
  return result;
}

TakeOver take_over(const ScenarioSettings& scenario, const Recording& recording,
                   const std::string& recording_id, std::int64_t step, const ReplayObserver& observer) {
  ReplayResult r = replay(scenario, recording, step, observer);
  Recording prefix;
  prefix.scenario = recording.scenario;
  prefix.parent = recording_id;
  prefix.branch_step = r.simulation->steps();
  prefix.total_steps = r.simulation->steps();
  prefix.ropes_settled = recording.ropes_settled;  // a replay of the branch starts as the original did
  prefix.ropes_curved = recording.ropes_curved;
  prefix.end_stops_clear = recording.end_stops_clear;
  prefix.start_settled = recording.start_settled;
  prefix.rope_damping_internal = recording.rope_damping_internal;
  prefix.sheave_bending_loss = recording.sheave_bending_loss;
  prefix.running_sheaves = recording.running_sheaves;
  prefix.slack_ropes_keep_sag = recording.slack_ropes_keep_sag;
  prefix.machine_state_hashed = recording.machine_state_hashed;
  // the branch records by this machine's labels: the prefix's controls are carried over to them
  const scene::ControlTable& table = r.simulation->control_table();
  for (const scene::ControlSpec& c : table.controls())
    prefix.control_labels.push_back(c.label);
  const BySlot by_slot(recording.control_labels, table);
  for (const auto& change : recording.inputs)
    if (change.step < prefix.branch_step) prefix.inputs.push_back({change.step, by_slot(change.controls)});
  for (const auto& checkpoint : recording.checkpoints)
    if (checkpoint.step <= prefix.branch_step) prefix.checkpoints.push_back(checkpoint);
  for (const auto& command : recording.commands)
    if (command.step < prefix.branch_step) prefix.commands.push_back(command);
  for (const auto& event : recording.team)
    if (event.step < prefix.branch_step) prefix.team.push_back(event);
  for (const auto& keyframe : recording.keyframes)
    if (keyframe.step <= prefix.branch_step) prefix.keyframes.push_back(keyframe);
  const scene::Controls levers = prefix.inputs.empty() ? table.neutral() : prefix.inputs.back().controls;
  return {std::move(r.simulation), Recorder(std::move(prefix)), levers};
}

}  // namespace harbour::sim
