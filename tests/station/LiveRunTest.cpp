// The station keeping real time for a minute: its own test binary, run alone (RUN_SERIAL), since what it
// measures is the machine's time.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "harbour/ig/RenderThread.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/sim/Autopilot.h"
#include "harbour/station/Session.h"
#include "scenes/StationScenes.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

// A 60 s live session on this machine: the autopilot drives at 1 kHz paced to the wall clock, the keeper
// records and evaluates off the step thread; then the recording replays bit for bit.
TEST(RealTimeLoop, ASixtySecondLiveRunKeepsOneKilohertz) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_station_live.db");
  options.record = scenes::temp_path("harbour_station_live.hsrc");
  Session session(exercise, options);
  sim::Autopilot pilot(exercise);
  session.loop().set_pilot([&](const sim::Simulation& s) { return pilot.next(s); });
  const auto start = std::chrono::steady_clock::now();
  session.start();
  std::this_thread::sleep_for(std::chrono::seconds(60));
  const SessionResult result = session.finish(SessionEnd::kInterrupted);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const LoopStats& s = result.loop;
  std::printf(
      "60 s live: %lld ticks, %lld late (>= 1 ms behind), %lld given up, longest tick %.0f us, mean "
      "%.1f us, worst lateness %.0f us, real-time factor %.4f, recorder waits %lld\n",
      static_cast<long long>(s.ticks), static_cast<long long>(s.late_ticks),
      static_cast<long long>(s.skipped_ticks), s.longest_tick_s * 1e6, s.mean_tick_s * 1e6,
      s.worst_lateness_s * 1e6, s.real_time_factor, static_cast<long long>(s.record_waits));
  EXPECT_TRUE(s.keeping_real_time);
  EXPECT_EQ(s.skipped_ticks, 0);
  EXPECT_NEAR(static_cast<double>(s.ticks), wall_s * 1000.0, 0.01 * wall_s * 1000.0);
  EXPECT_NEAR(s.real_time_factor, 1.0, 0.01);
  EXPECT_LT(static_cast<double>(s.late_ticks), 0.02 * static_cast<double>(s.ticks));
  EXPECT_LT(s.mean_tick_s, 0.5e-3);  // half the period: room for the image generator
  EXPECT_EQ(result.status, "interrupted");

  const sim::Recording recording = io::read_recording(options.record);
  EXPECT_EQ(recording.total_steps, s.steps);
  const sim::ReplayResult replay = sim::replay(exercise.scenario, recording);
  EXPECT_GE(replay.checkpoints_checked, 59);
  EXPECT_FALSE(replay.first_mismatch.has_value());
  // the step thread's keyframes, every ten seconds: a seek to the end starts from the last one (which must
  // give its second's recorded hash) and reaches the end's hash
  EXPECT_EQ(recording.keyframes.size(), static_cast<std::size_t>(s.steps / sim::Recorder::kKeyframeEvery));
  const sim::ReplayResult seek = sim::replay(exercise.scenario, recording, recording.total_steps);
  EXPECT_EQ(seek.keyframes_used, 1);
  EXPECT_FALSE(seek.first_mismatch.has_value());
  std::filesystem::remove(options.record);
}

// The image generator drawing the cab view as fast as it can beside the loop: the step keeps its time.
TEST(RealTimeLoop, TheImageGeneratorDrawingAlongsideDoesNotHoldTheStepBack) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_station_render.db");
  Session session(exercise, options);
  sim::Autopilot pilot(exercise);
  session.loop().set_pilot([&](const sim::Simulation& s) { return pilot.next(s); });
  ig::RenderThread render(
      session.simulation().scene(), ig::load_looks(std::string(HARBOUR_DATA_DIR) + "/visuals/harbour.yaml"),
      1280, 720, {ig::View{}}, [&] { return session.loop().latest_snapshot(kImageGeneratorReader); });
  session.start();
  std::this_thread::sleep_for(std::chrono::seconds(20));
  const double fps = render.fps();
  const long frames = render.frames();
  render.stop();
  const SessionResult result = session.finish(SessionEnd::kInterrupted);
  const LoopStats& s = result.loop;
  std::printf(
      "20 s live with the cab view drawn at 1280x720: %.1f fps (%ld frames); %lld ticks, %lld late, %lld "
      "given up, longest tick %.2f ms, real-time factor %.4f\n",
      fps, frames, static_cast<long long>(s.ticks), static_cast<long long>(s.late_ticks),
      static_cast<long long>(s.skipped_ticks), s.longest_tick_s * 1e3, s.real_time_factor);
  EXPECT_EQ(render.error(), "");
  EXPECT_GT(frames, 100);  // it does draw (>= 5 fps)
  EXPECT_EQ(s.skipped_ticks, 0);
  EXPECT_LT(static_cast<double>(s.late_ticks), 0.02 * static_cast<double>(s.ticks));
  EXPECT_NEAR(s.real_time_factor, 1.0, 0.01);
}

}  // namespace
}  // namespace harbour::station
