#include "harbour/station/RealTimeLoop.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/sim/Pilot.h"
#include "harbour/station/Session.h"
#include "scenes/StationScenes.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

// True once `condition` holds, polled every millisecond for up to 20 s.
template <typename Condition>
bool eventually(Condition condition) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

TEST(RealTimeLoop, CommandsFromOtherThreadsLandBetweenStepsAndAreRecorded) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_station_commands.db");
  options.record = scenes::temp_path("harbour_station_commands.hsrc");
  options.loop.time_scale = 10.0;
  Session session(exercise, options);
  sim::GantryAutopilot pilot(exercise);
  session.loop().set_pilot([&](const sim::Simulation& s) { return pilot.next(s); });
  session.start();
  // an instructor's console on another thread: a gust, fog, a freeze, a single step, resume
  std::thread console([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    LoopCommand gust{LoopCommand::Kind::kInstructor, {}};
    gust.instructor.gust = {0.0, 4.0, 6.0};
    EXPECT_TRUE(session.loop().post(gust));
    LoopCommand bad{LoopCommand::Kind::kInstructor, {}};
    bad.instructor.kind = sim::InstructorCommand::Kind::kSetVisibility;
    bad.instructor.value = -5.0;
    std::string why;
    EXPECT_FALSE(session.loop().post(bad, &why));  // refused at the edge, never reaches the step
    EXPECT_NE(why.find("visibility"), std::string::npos);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_TRUE(session.loop().post({LoopCommand::Kind::kHold, {}}));
  });
  console.join();
  // (waits by condition, not by the host's speed: a busy machine only takes longer)
  ASSERT_TRUE(eventually([&] { return session.loop().latest_snapshot(kConsoleReader)->held; }));
  const std::int64_t frozen_at = session.loop().stats().steps;
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(session.loop().stats().steps, frozen_at);  // held: no steps
  EXPECT_TRUE(session.loop().post({LoopCommand::Kind::kSingleStep, {}}));
  EXPECT_TRUE(eventually([&] { return session.loop().stats().steps == frozen_at + 1; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(session.loop().stats().steps, frozen_at + 1);
  const scene::Snapshot* snapshot = session.loop().latest_snapshot(0);
  ASSERT_NE(snapshot, nullptr);
  EXPECT_TRUE(snapshot->held);
  EXPECT_EQ(snapshot->step, frozen_at + 1);
  EXPECT_TRUE(session.loop().post({LoopCommand::Kind::kResume, {}}));
  EXPECT_TRUE(eventually([&] { return session.loop().stats().steps > frozen_at + 100; }));
  const SessionResult result = session.finish(SessionEnd::kInterrupted);

  const sim::Recording recording = io::read_recording(options.record);
  ASSERT_EQ(recording.commands.size(), 1u);
  EXPECT_EQ(recording.commands[0].command.kind, sim::InstructorCommand::Kind::kGust);
  EXPECT_GT(recording.commands[0].step, 0);
  const sim::ReplayResult replay = sim::replay(exercise.scenario, recording);
  EXPECT_FALSE(replay.first_mismatch.has_value());
  std::filesystem::remove(options.record);
}

// The bulk material reaches the image generator from the step thread: every grid, its heights as the
// simulation has them at the last hand-off (20 Hz), as the grab digs; an exercise without material hands
// none.
TEST(RealTimeLoop, TheBulkMaterialIsHandedToTheImageGeneratorAsItChanges) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/mhc_coal_discharge.yaml");
  sim::Simulation simulation(exercise.scenario);
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);  // the grab's
  RealTimeLoop loop(simulation);
  loop.set_pilot([&](const sim::Simulation& s) { return pilot->next(s); });
  const scene::BulkView* start = loop.latest_bulk(kImageGeneratorReader);
  ASSERT_NE(start, nullptr);
  ASSERT_EQ(start->grids.size(), 2u);  // the hold and the hopper
  const std::vector<float> hold_at_start = start->grids[0].heights;
  const bulk::BulkWorld& world = *simulation.bulk();
  StepRecord record;
  for (int second = 0; second < 40; ++second) {  // the grab's first bite is out of the hold
    loop.run_ticks(1000);                        // (every 50th step: a hand-off)
    while (loop.records().pop(record)) {         // the record keeper's side
    }
  }
  const scene::BulkView* now = loop.latest_bulk(kImageGeneratorReader);
  ASSERT_NE(now, nullptr);
  std::size_t changed = 0, differing = 0;
  for (std::size_t g = 0; g < now->grids.size(); ++g) {
    const scene::BulkView::Grid& grid = now->grids[g];
    ASSERT_EQ(grid.cells_x, world.grid(static_cast<int>(g)).cells_x());
    for (int j = 0; j < grid.cells_y; ++j)
      for (int i = 0; i < grid.cells_x; ++i) {
        const float h = grid.heights[static_cast<std::size_t>(j * grid.cells_x + i)];
        differing += h != static_cast<float>(world.grid(static_cast<int>(g)).height(i, j));
        if (g == 0) changed += h != hold_at_start[static_cast<std::size_t>(j * grid.cells_x + i)];
      }
  }
  EXPECT_EQ(differing, 0u);  // the simulation's heights at the last hand-off (step 40000)
  EXPECT_GT(changed, 100u);  // a bite: the hold's surface is not as it was

  const sim::ExerciseSettings boxes = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  sim::Simulation containers(boxes.scenario);
  EXPECT_EQ(RealTimeLoop(containers).latest_bulk(kConsoleReader), nullptr);
}

TEST(TripleBuffer, TheReaderAlwaysGetsTheNewestWholeValue) {
  TripleBuffer<std::array<std::int64_t, 64>> buffer;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::int64_t n = 1; n <= 200000; ++n) {
      buffer.back().fill(n);
      buffer.publish();
    }
    done = true;
  });
  std::int64_t last = 0, torn = 0, backwards = 0;
  while (!done.load()) {
    if (const auto* v = buffer.latest()) {
      for (const std::int64_t x : *v)
        torn += x != (*v)[0];
      backwards += (*v)[0] < last;
      last = (*v)[0];
    }
  }
  writer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_EQ((*buffer.latest())[0], 200000);
}

}  // namespace
}  // namespace harbour::station
