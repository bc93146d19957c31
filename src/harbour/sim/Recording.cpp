#include "harbour/sim/Recording.h"

#include <algorithm>
#include <string>

#include "harbour/core/StateArchive.h"

namespace harbour::sim {

Recorder::Recorder(std::string scenario, const ControlTable& controls) {
  recording_.scenario = std::move(scenario);
  for (const ControlSpec& c : controls.controls())
    recording_.control_labels.push_back(c.label);
}

std::vector<std::string> legacy_sts_control_labels() {
  return {"gantry",      "trolley",        "hoist",     "boom",        "lock",
          "unlock",      "emergency_stop", "horn",      "spreader_20", "spreader_40",
          "spreader_45", "flipper_1",      "flipper_2", "flipper_3",   "flipper_4"};
}

void Recorder::after_step(const Simulation& simulation, const Controls& given) {
  // store the controls as the machine read them, only when they change; the step they were applied at is one
  // before the current
  const Controls controls = simulation.control_table().in_range(given);
  const std::int64_t applied_at = simulation.steps() - 1;
  if (recording_.inputs.empty() || !(recording_.inputs.back().controls == controls)) {
    recording_.inputs.push_back({applied_at, controls});
    if (sink_) sink_->on_input(recording_.inputs.back());
  }
  if (simulation.steps() % kCheckpointEvery == 0) {
    recording_.checkpoints.push_back({simulation.steps(), simulation.state_hash()});
    if (sink_) sink_->on_checkpoint(recording_.checkpoints.back());
  }
  if (simulation.steps() % kKeyframeEvery == 0) {
    recording_.keyframes.push_back({simulation.steps(), simulation.save_state()});
    if (sink_) sink_->on_keyframe(recording_.keyframes.back());
  }
  recording_.total_steps = simulation.steps();
}

void Recorder::on_command(const Simulation& simulation, const InstructorCommand& command) {
  recording_.commands.push_back({simulation.steps(), command});
  if (sink_) sink_->on_command(recording_.commands.back());
}

namespace {
// recorded values (by the recording's labels) at this machine's slots
class BySlot {
 public:
  BySlot(const std::vector<std::string>& labels, const ControlTable& table) : table_(table) {
    for (const std::string& label : labels) {
      slot_of_.push_back(table.find(label));
      if (slot_of_.back() < 0)
        throw core::StateError("the recording has a control '" + label + "' this machine does not");
    }
  }
  /// Throws core::StateError at a value the control cannot take (the recorder stores them as read).
  Controls operator()(const Controls& recorded) const {
    Controls c = table_.neutral();
    for (std::size_t n = 0; n < slot_of_.size(); ++n)
      c.value[static_cast<std::size_t>(slot_of_[n])] = recorded.value[n];
    const Controls read = table_.in_range(c);
    for (std::size_t n = 0; n < slot_of_.size(); ++n) {
      const auto slot = static_cast<std::size_t>(slot_of_[n]);
      if (!(read.value[slot] == c.value[slot]))
        throw core::StateError("the recording's control '" + table_[slot_of_[n]].label + "' holds " +
                               std::to_string(c.value[slot]) + ", a value it cannot take");
    }
    return c;
  }

 private:
  const ControlTable& table_;
  std::vector<int> slot_of_;
};
}  // namespace

ReplayResult replay(const ScenarioSettings& scenario, const Recording& recording, std::int64_t stop_step,
                    const ReplayObserver& observer) {
  ReplayResult result;
  result.simulation = std::make_unique<Simulation>(scenario);
  Simulation& sim = *result.simulation;
  const std::int64_t end = stop_step < 0 ? recording.total_steps : std::min(stop_step, recording.total_steps);
  if (stop_step >= 0 && !observer) {
    const Recording::Keyframe* start = nullptr;
    for (const Recording::Keyframe& k : recording.keyframes)
      if (k.step <= end) start = &k;
    if (start) {
      sim.restore_state(start->state);
      ++result.keyframes_used;
      // a keyframe that does not give its second's recorded hash would replay a state that never was
      for (const Recording::Checkpoint& c : recording.checkpoints)
        if (c.step == start->step && c.state_hash != sim.state_hash())
          throw core::StateError("the keyframe at step " + std::to_string(start->step) +
                                 " does not give the state hash recorded there (a damaged recording)");
    }
  }
  std::size_t next_input = 0, next_checkpoint = 0, next_command = 0;
  // a keyframe holds the commands before its step; those at its step came after it was taken
  while (next_command < recording.commands.size() && recording.commands[next_command].step < sim.steps())
    ++next_command;
  const BySlot by_slot(recording.control_labels, sim.control_table());
  Controls current = sim.control_table().neutral();
  while (sim.steps() < end) {
    while (next_command < recording.commands.size() && recording.commands[next_command].step == sim.steps())
      sim.command(recording.commands[next_command++].command);
    while (next_input < recording.inputs.size() && recording.inputs[next_input].step <= sim.steps())
      current = by_slot(recording.inputs[next_input++].controls);
    sim.single_step(current);  // replay ignores the freeze: held periods were not recorded as steps
    if (observer) observer(sim, current);
    while (next_checkpoint < recording.checkpoints.size() &&
           recording.checkpoints[next_checkpoint].step < sim.steps())
      ++next_checkpoint;
    if (next_checkpoint < recording.checkpoints.size() &&
        recording.checkpoints[next_checkpoint].step == sim.steps()) {
      ++result.checkpoints_checked;
      if (!result.first_mismatch && recording.checkpoints[next_checkpoint].state_hash != sim.state_hash())
        result.first_mismatch = sim.steps();
      ++next_checkpoint;
    }
  }
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
  // the branch records by this machine's labels: the prefix's controls are carried over to them
  const ControlTable& table = r.simulation->control_table();
  for (const ControlSpec& c : table.controls())
    prefix.control_labels.push_back(c.label);
  const BySlot by_slot(recording.control_labels, table);
  for (const auto& change : recording.inputs)
    if (change.step < prefix.branch_step) prefix.inputs.push_back({change.step, by_slot(change.controls)});
  for (const auto& checkpoint : recording.checkpoints)
    if (checkpoint.step <= prefix.branch_step) prefix.checkpoints.push_back(checkpoint);
  for (const auto& command : recording.commands)
    if (command.step < prefix.branch_step) prefix.commands.push_back(command);
  for (const auto& keyframe : recording.keyframes)
    if (keyframe.step <= prefix.branch_step) prefix.keyframes.push_back(keyframe);
  return {std::move(r.simulation), Recorder(std::move(prefix))};
}

}  // namespace harbour::sim
