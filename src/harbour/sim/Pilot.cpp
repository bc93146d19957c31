#include "harbour/sim/Pilot.h"

#include <stdexcept>

#include "harbour/sim/Evaluation.h"
#include "harbour/sim/MachineType.h"
#include "harbour/sim/Simulation.h"

namespace harbour::sim {

namespace {

// A good operator's hands at a power failure: off the levers until the drives are back (so centred, as the
// zero-voltage protection asks), the scripted plan carrying on underneath.
class HandsOffWhenThePowerFails final : public Pilot {
 public:
  explicit HandsOffWhenThePowerFails(std::unique_ptr<Pilot> pilot) : pilot_(std::move(pilot)) {}
  scene::Controls next(const Simulation& simulation) override {
    const scene::Controls planned = pilot_->next(simulation);
    return simulation.power_off() || simulation.awaiting_zero() ? simulation.control_table().neutral()
                                                                : planned;
  }
  const char* activity() const override { return pilot_->activity(); }
  void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) override {
    pilot_->resume(simulation, moves_done, levers);
  }

 private:
  std::unique_ptr<Pilot> pilot_;
};

// the machine type's scripted operators (machines/<kind>/Type.cpp)
std::span<const PilotType> pilots_for(const ExerciseSettings& exercise) {
  return exercise.scenario.machine.type().pilots;
}

std::unique_ptr<Pilot> scripted_operator(const ExerciseSettings& exercise) {
  for (const PilotType& pilot : pilots_for(exercise))
    if (pilot.why_cannot_drive(exercise).empty()) return pilot.make(exercise);
  throw std::invalid_argument(why_no_pilot(exercise));
}

}  // namespace

std::string why_no_pilot(const ExerciseSettings& exercise) {
  std::string reasons;
  for (const PilotType& pilot : pilots_for(exercise)) {
    const std::string why = pilot.why_cannot_drive(exercise);
    if (why.empty()) return "";
    reasons += (reasons.empty() ? "" : "; ") + why;
  }
  return "no scripted operator drives it (" + (reasons.empty() ? "the machine has none" : reasons) + ")";
}

std::unique_ptr<Pilot> make_pilot(const ExerciseSettings& exercise) {
  return std::make_unique<HandsOffWhenThePowerFails>(scripted_operator(exercise));
}

}  // namespace harbour::sim
