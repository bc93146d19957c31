#pragma once

#include <memory>
#include <string>

#include "harbour/scene/Controls.h"

namespace harbour::sim {

struct ExerciseSettings;
class Simulation;

/// A scripted operator for an exercise, whichever machine runs it: headless runs, demos, the station's
/// --autopilot, take-overs, tests.
class Pilot {
 public:
  virtual ~Pilot() = default;
  /// The controls for the next step, from what the simulation shows now.
  virtual scene::Controls next(const Simulation& simulation) = 0;
  /// What it is doing now, for progress displays.
  virtual const char* activity() const = 0;
  /// Takes over a running exercise (an instructor's take-over) of which `moves_done` container moves are
  /// made, with the levers where they stand (`levers`): its hands start from there, not from neutral.
  virtual void resume(const Simulation& simulation, int moves_done, const scene::Controls& levers) = 0;
};

/// Deliberate faults for a scripted bad driver of a vehicle (tests of the evaluation).
struct DriverDefects {
  bool ignore_route = false;            ///< drive straight for the target, whatever stands in the way
  bool reverse_steering_wrong = false;  ///< reversing a trailer, steer the way its rear is to go
};

/// Why no scripted operator can drive `exercise` ("" when one can): its machine type's operators
/// (MachineType::pilots) are asked in turn.
std::string why_no_pilot(const ExerciseSettings& exercise);
/// The scripted operator for `exercise`, its hands off the levers while the power is off and until the drives
/// are back; throws std::invalid_argument with why_no_pilot() when there is none.
std::unique_ptr<Pilot> make_pilot(const ExerciseSettings& exercise);

}  // namespace harbour::sim
