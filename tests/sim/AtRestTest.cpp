#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Simulation.h"

namespace harbour::sim {
namespace {

// A machine, left alone in still air on a calm sea, comes to rest: the kinetic energy of everything the
// solver moves decays and never grows again (no model pumps energy in: the ropes' waves, the tyres' holds,
// the bulk contacts, the joints). Peaks over 20 s windows, 120 s in all.
class LeftAlone : public testing::TestWithParam<const char*> {};

TEST_P(LeftAlone, ComesToRestAndStaysThere) {
  ScenarioSettings scenario =
      io::load_exercise(std::string(HARBOUR_DATA_DIR "/exercises/") + GetParam() + ".yaml").scenario;
  scenario.weather.wind_mean_mps = 0.0;
  scenario.weather.turbulence_intensity = 0.0;
  scenario.events.clear();
  scenario.lift_events.clear();
  if (scenario.vessel) scenario.vessel->sea = {};
  scenario.trucks.trucks = 0;
  Simulation sim(scenario);
  const Controls neutral = sim.control_table().neutral();
  std::vector<double> peaks;
  for (int window = 0; window < 6; ++window) {
    double peak = 0.0;
    for (int k = 0; k < 20000; ++k) {
      sim.step(neutral);
      peak = std::max(peak, sim.world().kinetic_energy_j());
    }
    peaks.push_back(peak);
  }
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
  std::printf("%s: peak kinetic energy per 20 s:", GetParam());
  for (const double p : peaks)
    std::printf(" %.3g", p);
  std::printf(" J\n");
  for (std::size_t n = 2; n < peaks.size(); ++n)
    EXPECT_LE(peaks[n], 1.05 * peaks[n - 1] + 1e-3) << "window " << n << " grew";
  EXPECT_LT(peaks.back(), 1.0) << "still moving after 100 s";
}

// Not yet the MHC: in still air its hook's swing grows (31.7 to 33.6 J over 100 s in mhc_hook_lift; ten times
// the ropes' transverse damping makes it grow faster, so the wave's frame, turning with the swinging chord,
// feeds it) and its grab's swing keeps 10.7 J. Nor the reach stacker: three of its bodies report 355 J of
// velocity while they stand still.
INSTANTIATE_TEST_SUITE_P(EveryMachine, LeftAlone,
                         testing::Values("sts_discharge", "rtg_rehandle", "tractor_free_practice"));

}  // namespace
}  // namespace harbour::sim
