#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/MotionFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/machines/sts/Files.h"
#include "harbour/machines/tractor/TerminalTractor.h"
#include "harbour/motion/MotionSystem.h"
#include "harbour/sim/Simulation.h"

namespace harbour::sim {
namespace {

// The platform's commands from a run of the simulation, as the station makes them: the cab's cue from each
// published state through the washout of the machine that runs (its data file's motion cues)
struct PlatformRun {
  motion::MotionSystem system;
  double peak_surge_m = 0.0, peak_pitch_rad = 0.0;
  explicit PlatformRun(const Simulation& sim) : system(settings(sim.machine().kind()), 1) {}
  static motion::MotionSettings settings(const std::string& machine) {
    const auto platform = io::load_platform(HARBOUR_DATA_DIR "/motion/platform.yaml");
    motion::MotionSettings s;
    s.washout = io::load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml",
                                 std::string(HARBOUR_DATA_DIR "/machines/") + machine + ".yaml");
    s.geometry = platform.geometry;
    s.limits = platform.limits;
    return s;
  }
  // steps the simulation with `controls` for `seconds`, a platform frame every 10 ms
  template <class ControlsOf>
  void run(Simulation& sim, double seconds, ControlsOf controls_of, bool measure) {
    const int steps = static_cast<int>(std::lround(seconds / Simulation::kStep_s));
    for (int k = 1; k <= steps; ++k) {
      sim.step(controls_of(sim));
      if (k % 10 != 0) continue;
      const auto snap = sim.snapshot();
      const motion::PlatformFrame f =
          system.step({snap->cab.specific_force_mps2, snap->cab.angular_velocity_radps});
      if (!measure) continue;
      peak_surge_m = std::max(peak_surge_m, std::abs(f.pose[motion::kSurge]));
      peak_pitch_rad = std::max(peak_pitch_rad, std::abs(f.pose[motion::kPitch]));
    }
  }
};

double& control(scene::Controls& c, const Simulation& sim, const char* name) {
  return c.value[static_cast<std::size_t>(sim.control_table().find(name))];
}

// the tractor's controls in forward gear
scene::Controls forward(const Simulation& s) {
  scene::Controls c = s.control_table().neutral();
  const std::vector<std::string>& positions =
      s.control_table()[s.control_table().find("direction")].positions;
  control(c, s, "direction") =
      static_cast<double>(std::find(positions.begin(), positions.end(), "forward") - positions.begin());
  return c;
}

// each machine's data file cues it its own way: some channel's gain is not the washout file's default
TEST(MotionCue, EveryMachineFileCarriesItsOwnMotionCues) {
  const motion::WashoutSettings defaults = io::load_washout(
      io::YamlFile::load(HARBOUR_DATA_DIR "/motion/washout.yaml"), io::YamlFile::parse("{}", "none.yaml"));
  for (const std::string_view kind : machine_kinds()) {
    const motion::WashoutSettings w =
        io::load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml",
                         std::string(HARBOUR_DATA_DIR "/machines/") + std::string(kind) + ".yaml");
    EXPECT_TRUE(w.surge_sway.gain != defaults.surge_sway.gain || w.heave.gain != defaults.heave.gain ||
                w.tilt.gain != defaults.tilt.gain || w.rotation.gain != defaults.rotation.gain)
        << kind;
    EXPECT_EQ(w.rate_hz, defaults.rate_hz) << kind;
  }
}

TEST(MotionCue, ATractorsBrakingAndAnStsTrolleyStopGiveDifferentPlatformCommands) {
  // the tractor at 6 m/s braked hard; the STS trolley at full speed stopped: each through its own washout
  Simulation tractor(io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_free_practice.yaml").scenario);
  ASSERT_STREQ(tractor.machine().kind(), "tractor");
  PlatformRun tractor_platform(tractor);
  const auto drive = [](const Simulation& s) {
    scene::Controls c = forward(s);
    control(c, s, "throttle") = 1.0;
    return c;
  };
  const auto brake = [](const Simulation& s) {
    scene::Controls c = forward(s);
    control(c, s, "brake") = 1.0;
    return c;
  };
  tractor_platform.run(tractor, 6.0, drive, false);
  const double speed = dynamic_cast<const TerminalTractor&>(tractor.machine()).forward_mps();
  ASSERT_GT(speed, 4.0);
  tractor_platform.run(tractor, 5.0, brake, true);

  Simulation sts(io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml").scenario);
  ASSERT_STREQ(sts.machine().kind(), "sts");
  PlatformRun sts_platform(sts);
  const auto travel = [](const Simulation& s) {
    scene::Controls c = s.control_table().neutral();
    control(c, s, "trolley") = 1.0;
    return c;
  };
  const auto stop = [](const Simulation& s) { return s.control_table().neutral(); };
  sts_platform.run(sts, 8.0, travel, false);
  sts_platform.run(sts, 5.0, stop, true);

  std::printf(
      "platform peaks: tractor braking surge %.3f m pitch %.2f deg; STS trolley stop surge %.3f m pitch "
      "%.2f deg\n",
      tractor_platform.peak_surge_m, tractor_platform.peak_pitch_rad * 180.0 / std::numbers::pi,
      sts_platform.peak_surge_m, sts_platform.peak_pitch_rad * 180.0 / std::numbers::pi);
  EXPECT_GT(sts_platform.peak_surge_m, 0.001);  // the trolley's stop is felt
  EXPECT_GT(tractor_platform.peak_surge_m, 10.0 * sts_platform.peak_surge_m);
  // the trolley's sustained deceleration is rendered by tilting the cab: asin(gain a / g), the second-order
  // low-pass overshooting by a few per cent
  const double decel =
      io::load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml").trolley_drive.deceleration_mps2;
  const double tilt =
      std::asin(PlatformRun::settings("sts").washout.tilt.gain * decel / core::kStandardGravity);
  EXPECT_NEAR(sts_platform.peak_pitch_rad, tilt, 0.15 * tilt);
  EXPECT_GT(tractor_platform.peak_pitch_rad, 0.0);
}

}  // namespace
}  // namespace harbour::sim
