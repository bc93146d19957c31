// Motion cueing benchmarks: cost per platform step. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <cmath>

#include "harbour/core/Units.h"
#include "harbour/io/MotionFiles.h"
#include "harbour/motion/MotionSystem.h"

namespace harbour {
namespace {

motion::MotionSettings settings() {
  const auto platform = io::load_platform(HARBOUR_DATA_DIR "/motion/platform.yaml");
  motion::MotionSettings s;
  s.washout =
      io::load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml", HARBOUR_DATA_DIR "/machines/tractor.yaml");
  s.geometry = platform.geometry;
  s.limits = platform.limits;
  return s;
}

// a tractor weaving and braking: varying specific force and yaw rate
motion::MotionCue cue_at(int k) {
  motion::MotionCue c;
  const double t = k * 0.01;
  c.specific_force_mps2 = {1.5 * std::sin(0.7 * t), 1.0 * std::sin(1.3 * t),
                           core::kStandardGravity + 0.3 * std::sin(9 * t)};
  c.angular_velocity_rad_s = {0.02 * std::sin(3 * t), 0.02 * std::sin(2 * t), 0.2 * std::sin(1.3 * t)};
  return c;
}

void BM_WashoutAndInverseKinematics(benchmark::State& state) {
  const motion::MotionSettings s = settings();
  motion::ClassicalWashout washout(s.washout);
  const motion::StewartPlatform platform(s.geometry);
  int k = 0;
  for (auto _ : state) {
    const motion::PlatformPose pose = washout.step(cue_at(k++));
    benchmark::DoNotOptimize(platform.inverse(pose));
  }
}
BENCHMARK(BM_WashoutAndInverseKinematics);

void BM_MotionSystemStep(benchmark::State& state) {
  motion::MotionSystem system(settings());
  int k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(system.step(cue_at(k++)));
}
BENCHMARK(BM_MotionSystemStep);

void BM_ForwardKinematics(benchmark::State& state) {
  const motion::StewartPlatform platform(settings().geometry);
  motion::PlatformPose target;
  target[motion::kSurge] = 0.1;
  target[motion::kPitch] = 0.08;
  target[motion::kYaw] = -0.05;
  const motion::ActuatorLengths lengths = platform.inverse(target);
  for (auto _ : state) {
    motion::PlatformPose guess;
    benchmark::DoNotOptimize(platform.forward(lengths, guess));
  }
}
BENCHMARK(BM_ForwardKinematics);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
