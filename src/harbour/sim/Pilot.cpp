#include "harbour/sim/Pilot.h"

#include <stdexcept>

#include "harbour/sim/Autopilot.h"
#include "harbour/sim/GrabAutopilot.h"
#include "harbour/sim/HookAutopilot.h"
#include "harbour/sim/ReachStackerAutopilot.h"
#include "harbour/sim/TractorAutopilot.h"

namespace harbour::sim {

namespace {

// A good operator's hands at a power failure: off the levers until the drives are back (so centred, as the
// zero-voltage protection asks), the scripted plan carrying on underneath.
class HandsOffWhenThePowerFails final : public Pilot {
 public:
  explicit HandsOffWhenThePowerFails(std::unique_ptr<Pilot> pilot) : pilot_(std::move(pilot)) {}
  Controls next(const Simulation& simulation) override {
    const Controls planned = pilot_->next(simulation);
    return simulation.power_off() || simulation.awaiting_zero() ? simulation.control_table().neutral()
                                                                : planned;
  }
  const char* activity() const override { return pilot_->activity(); }
  void resume(const Simulation& simulation, int moves_done) override {
    pilot_->resume(simulation, moves_done);
  }

 private:
  std::unique_ptr<Pilot> pilot_;
};

std::unique_ptr<Pilot> scripted_operator(const ExerciseSettings& exercise) {
  if (Autopilot::why_cannot_drive(exercise).empty()) return std::make_unique<Autopilot>(exercise);
  if (GrabAutopilot::why_cannot_drive(exercise).empty()) return std::make_unique<GrabAutopilot>(exercise);
  if (HookAutopilot::why_cannot_drive(exercise).empty()) return std::make_unique<HookAutopilot>(exercise);
  if (TractorAutopilot::why_cannot_drive(exercise).empty())
    return std::make_unique<TractorAutopilot>(exercise);
  if (ReachStackerAutopilot::why_cannot_drive(exercise).empty())
    return std::make_unique<ReachStackerAutopilot>(exercise);
  throw std::invalid_argument(why_no_pilot(exercise));
}

}  // namespace

std::string why_no_pilot(const ExerciseSettings& exercise) {
  const std::string container = Autopilot::why_cannot_drive(exercise);
  if (container.empty()) return "";
  const std::string grab = GrabAutopilot::why_cannot_drive(exercise);
  if (grab.empty()) return "";
  const std::string hook = HookAutopilot::why_cannot_drive(exercise);
  if (hook.empty()) return "";
  const std::string tractor = TractorAutopilot::why_cannot_drive(exercise);
  if (tractor.empty()) return "";
  const std::string stacker = ReachStackerAutopilot::why_cannot_drive(exercise);
  if (stacker.empty()) return "";
  return "no scripted operator drives it (" + container + "; " + grab + "; " + hook + "; " + tractor + "; " +
         stacker + ")";
}

std::unique_ptr<Pilot> make_pilot(const ExerciseSettings& exercise) {
  return std::make_unique<HandsOffWhenThePowerFails>(scripted_operator(exercise));
}

}  // namespace harbour::sim
