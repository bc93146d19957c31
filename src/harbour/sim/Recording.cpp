#include "harbour/sim/Recording.h"

#include <algorithm>
#include <string>

#include "harbour/core/StateArchive.h"

namespace harbour::sim {

void Recorder::after_step(const Simulation& simulation, const Inputs& given) {
  // store inputs as the machine read them, only when they change; the step they were applied at is one
  // before the current
  const Inputs inputs = in_range(given);
  const std::int64_t applied_at = simulation.steps() - 1;
  if (recording_.inputs.empty() || !(recording_.inputs.back().inputs == inputs)) {
    recording_.inputs.push_back({applied_at, inputs});
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
  Inputs current;
  while (sim.steps() < end) {
    while (next_command < recording.commands.size() && recording.commands[next_command].step == sim.steps())
      sim.command(recording.commands[next_command++].command);
    while (next_input < recording.inputs.size() && recording.inputs[next_input].step <= sim.steps())
      current = recording.inputs[next_input++].inputs;
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
  for (const auto& change : recording.inputs)
    if (change.step < prefix.branch_step) prefix.inputs.push_back(change);
  for (const auto& checkpoint : recording.checkpoints)
    if (checkpoint.step <= prefix.branch_step) prefix.checkpoints.push_back(checkpoint);
  for (const auto& command : recording.commands)
    if (command.step < prefix.branch_step) prefix.commands.push_back(command);
  for (const auto& keyframe : recording.keyframes)
    if (keyframe.step <= prefix.branch_step) prefix.keyframes.push_back(keyframe);
  return {std::move(r.simulation), Recorder(std::move(prefix))};
}

}  // namespace harbour::sim
