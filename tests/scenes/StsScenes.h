#pragma once

// An STS discharge scene and a scripted operator: shared by the simulation, recording and benchmark code.

#include <string>

#include "harbour/io/MachineFiles.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Simulation.h"

namespace harbour::scenes {

/// The crane over a vessel moored at the quay: a deck block 8 m high at x = 30..54 m carrying three 40 ft
/// containers (ISO 668: 12.192 x 2.438 x 2.591 m) side by side; the trolley starts over the middle one.
inline sim::ScenarioSettings sts_discharge(const std::string& data_dir) {
  sim::ScenarioSettings s;
  s.name = "sts_discharge_test";
  s.crane = io::load_sts_crane(data_dir + "/machines/sts.yaml");
  s.gantry_y_m = 0.0;
  s.trolley_x_m = 42.0;
  s.spreader_z_m = 20.0;
  s.blocks.push_back({{12.0, 20.0, 4.0}, {42.0, 0.0, 4.0}});
  const core::Vec3 half{12.192 / 2, 2.438 / 2, 2.591 / 2};
  for (int n = -1; n <= 1; ++n)
    s.containers.push_back(
        {"BOX" + std::to_string(n + 2), half, 22000.0, {42.0, 3.0 * n, 8.0 + half.z}, 0.0});
  return s;
}

/// Discharge exercise: BOX2 from the vessel onto a truck chassis (a 1.5 m high block) on the quay at x = 8 m.
inline sim::ExerciseSettings sts_discharge_exercise(const std::string& data_dir) {
  sim::ExerciseSettings e;
  e.name = "discharge_one";
  e.scenario = sts_discharge(data_dir);
  e.scenario.blocks.push_back({{6.2, 1.3, 0.75}, {8.0, 0.0, 0.75}});  // truck chassis, 1.5 m deck height
  e.moves.push_back({"BOX2", {8.0, 0.0, 1.5 + 2.591 / 2}, 0.3});
  e.rules.time_limit_s = 180.0;
  return e;
}

/// A scripted operator: trolley out and back, lowering, a lock attempt, hoisting with some gantry travel.
inline sim::Inputs scripted_operator(std::int64_t step) {
  const double t = static_cast<double>(step) * 0.001;
  sim::Inputs in;
  if (t < 3.0)
    in.sts.trolley = 0.3;
  else if (t < 6.0)
    in.sts.trolley = -0.3;
  else if (t < 11.0)
    in.sts.hoist = -0.25;
  else if (t < 11.2)
    in.sts.lock = true;
  else if (t < 18.0) {
    in.sts.hoist = 0.4;
    in.sts.gantry = 0.5;
  }
  return in;
}

}  // namespace harbour::scenes
