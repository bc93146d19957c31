#pragma once

#include <cstdint>
#include <stdexcept>
#include <utility>

#include "harbour/sim/Pilot.h"
#include "harbour/sim/Simulation.h"

namespace harbour::sim {

/// A scripted operator of one machine type that decides its levers 50 times a second, as a hand moves them,
/// and holds them between decisions. Its subclass decides from the simulation and its machine.
template <typename MachineT>
class DecidingPilot : public Pilot {
 public:
  /// Steps between two decisions (50 Hz at the executive's 1 kHz).
  static constexpr std::int64_t kDecisionSteps = 20;

  /// The controls for the next step (decided 50 times a second, held in between).
  scene::Controls next(const Simulation& simulation) final {
    if (simulation.steps() % kDecisionSteps != 0 && decided_) return last_;
    const auto* machine = dynamic_cast<const MachineT*>(&simulation.machine());
    if (!machine || !drives(simulation, *machine))
      throw std::logic_error("a scripted operator's exercise runs on a machine it does not drive");
    const scene::Controls decided = decide(simulation, *machine);
    before_last_ = std::exchange(last_, decided);
    decided_ = true;
    return last_;
  }

 protected:
  /// The levers for the coming 20 steps.
  virtual scene::Controls decide(const Simulation& simulation, const MachineT& machine) = 0;
  /// Whether the machine is one it drives beyond its type (a grab, not a hook).
  virtual bool drives(const Simulation&, const MachineT&) const { return true; }
  /// Taken over with the levers where they stand: the next step decides afresh, from them.
  void take_levers(const scene::Controls& levers) {
    last_ = before_last_ = levers;
    decided_ = false;
  }
  /// Whether the coming decision is its first since it started or took over (its filters start afresh).
  bool first_decision() const { return !decided_; }
  /// Its last decision and the one before (how fast each lever was moving).
  const scene::Controls& last_decision() const { return last_; }
  const scene::Controls& decision_before_last() const { return before_last_; }

 private:
  scene::Controls last_{};
  scene::Controls before_last_{};
  bool decided_ = false;
};

}  // namespace harbour::sim
