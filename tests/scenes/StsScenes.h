#pragma once

// An STS discharge scene and a scripted operator: shared by the simulation, recording and benchmark code.

#include <string>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/sts/Files.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Simulation.h"

namespace harbour::scenes {

/// The shipped discharge exercise (data/exercises/sts_discharge.yaml): the crane over a feeder's bay 12
/// with three 40 ft boxes on its hatch covers, a truck under the crane, one move (TGHU1000012 onto the
/// truck).
inline sim::ExerciseSettings sts_discharge_exercise(const std::string& data_dir) {
  return io::load_exercise(data_dir + "/exercises/sts_discharge.yaml");
}

/// Its world alone, for tests that drive the crane themselves.
inline sim::ScenarioSettings sts_discharge(const std::string& data_dir) {
  return sts_discharge_exercise(data_dir).scenario;
}

/// The shipped STS's controls (its machine file, data/machines/sts.yaml).
inline const scene::ControlTable& sts_controls() {
  static const scene::ControlTable table = io::load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml").controls;
  return table;
}

/// The STS cab's controls as the executive takes them (the shipped STS control table, which scenes use).
inline scene::Controls cab(const sim::StsControls& sts) {
  const scene::ControlTable& table = sts_controls();
  static const sim::StsControlSlots slots(table);
  scene::Controls c = table.neutral();
  slots.write(sts, c);
  return c;
}

/// A scripted operator: trolley out and back, lowering, a lock attempt, hoisting with some gantry travel.
inline sim::StsControls scripted_operator(std::int64_t step) {
  const double t = static_cast<double>(step) * 0.001;
  sim::StsControls in;
  if (t < 3.0)
    in.trolley = 0.3;
  else if (t < 6.0)
    in.trolley = -0.3;
  else if (t < 11.0)
    in.hoist = -0.25;
  else if (t < 11.2)
    in.lock = true;
  else if (t < 18.0) {
    in.hoist = 0.4;
    in.gantry = 0.5;
  }
  return in;
}

}  // namespace harbour::scenes
