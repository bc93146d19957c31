// Another team member's machine as this simulation's obstacle (TeamInput::kObstacleAt): a kinematic box this
// machine hits and is stopped by, counted as a vehicle collision, gone once its member leaves, and replayed
// bit for bit from the recorded inputs (from the start and from a keyframe taken while it stood there).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/machines/tractor/TerminalTractor.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Recording.h"

namespace harbour::sim {
namespace {

// the cab's controls: a throttle holding `speed_mps` forward (brake above it), the wheel straight
scene::Controls driving(const Simulation& sim, double speed_mps) {
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = table.neutral();
  const double error =
      speed_mps - std::abs(dynamic_cast<const TerminalTractor&>(sim.machine()).forward_mps());
  c.value[static_cast<std::size_t>(table.find("throttle"))] = std::clamp(0.5 * error, 0.0, 1.0);
  c.value[static_cast<std::size_t>(table.find("brake"))] = std::clamp(-0.5 * error, 0.0, 1.0);
  const std::vector<std::string>& positions = table[table.find("direction")].positions;
  c.value[static_cast<std::size_t>(table.find("direction"))] =
      static_cast<double>(std::find(positions.begin(), positions.end(), "forward") - positions.begin());
  return c;
}

TEST(TeamObstacles, ATractorDrivenIntoAnotherMembersTractorIsStoppedByItAndItIsAVehicleCollision) {
  const ExerciseSettings exercise =
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_free_practice.yaml");
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  Recorder recorder(exercise.name, sim.control_table());
  const auto run = [&](double seconds, double speed_mps) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k) {
      const scene::Controls c = driving(sim, speed_mps);
      sim.step(c);
      evaluator.observe(sim, c);
      recorder.after_step(sim, c);
    }
    ASSERT_FALSE(sim.diverged()) << sim.divergence();
  };
  const auto input = [&](const TeamInput& in) {  // as a station applies one: before the next step, recorded
    sim.team_input(in);
    recorder.on_team(sim.steps(), in);
  };
  run(2.0, 0.0);
  // another tractor like this one, standing 14 m ahead of it (centre to centre), square to the lane
  const physics::BodyId body = sim.machine().cab_body();
  const core::Pose start = sim.world().pose(body);
  const core::Vec3 ahead = start.rotation.column(0), half = sim.scene().entities[0].half_extents_m;
  TeamInput other;
  other.kind = TeamInput::Kind::kObstacleAt;
  other.slot = 0;
  other.pose = {start.rotation, start.position + 14.0 * ahead};
  other.half_extents_m = half;
  input(other);
  EXPECT_EQ(sim.obstacles().count(), 1);
  const auto gap_m = [&] {  // its front to the other's rear, along the lane
    return core::dot(other.pose.position - sim.world().pose(body).position, ahead) - 2.0 * half.x;
  };
  const double gap_before = gap_m();
  // driven at it at 3 m/s and held there with the throttle on
  double least_gap = 1e9;
  for (int s = 0; s < 14; ++s) {
    run(1.0, 3.0);
    least_gap = std::min(least_gap, gap_m());
  }
  const double held_gap = gap_m();
  const double speed = std::abs(dynamic_cast<const TerminalTractor&>(sim.machine()).forward_mps());
  std::printf(
      "a tractor at 3 m/s into another's: gap %.2f m before, %.3f m at least, %.3f m held, %.3f m/s; "
      "%d collisions (%d vehicle), worst %.2f m/s\n",
      gap_before, least_gap, held_gap, speed, evaluator.metrics().collisions,
      evaluator.metrics().vehicle_collisions, evaluator.metrics().worst_collision_mps);
  EXPECT_GT(gap_before, 5.0);
  EXPECT_LT(held_gap, 1.0);     // it reached the other (its boxes are near its collision shapes)
  EXPECT_GT(least_gap, -0.15);  // and did not drive through it
  EXPECT_LT(speed, 0.2);
  EXPECT_GE(evaluator.metrics().vehicle_collisions, 1);
  EXPECT_GT(evaluator.metrics().worst_collision_mps, 1.0);

  // the other's member leaves: gone, it touches nothing, and the tractor drives on where it stood
  other.half_extents_m = {};
  input(other);
  run(8.0, 3.0);
  EXPECT_LT(gap_m(), -10.0);

  // the recording replays bit for bit, from the start and from a keyframe taken while the other stood there
  const Recording& recording = recorder.recording();
  const ReplayResult whole = replay(exercise.scenario, recording);
  EXPECT_FALSE(whole.first_mismatch.has_value()) << *whole.first_mismatch;
  EXPECT_EQ(whole.simulation->obstacles().count(), 1);
  ReplayPlayer player(exercise.scenario, recording);
  player.seek(12'500);
  EXPECT_EQ(player.keyframes_used(), 1);
  player.advance_to(recording.total_steps);
  EXPECT_FALSE(player.first_mismatch().has_value()) << *player.first_mismatch();
  EXPECT_GE(player.checkpoints_checked(), 10);
}

TEST(TeamObstacles, TheCranesSpreaderLoweredOntoATractorsCabHitsIt) {
  // the crane of a team: a tractor's cab (another member's machine) stands 4 m under its empty spreader,
  // which is lowered at full lever onto it
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge_team.yaml");
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  const auto& sts = dynamic_cast<const StsCrane&>(sim.machine());
  const core::Pose spreader = sts.spreader_pose();
  TeamInput cab;
  cab.kind = TeamInput::Kind::kObstacleAt;
  cab.half_extents_m = {3.0, 1.25, 1.5};
  cab.pose.position = spreader.position - core::Vec3{0, 0, sts.spreader_half_extents_m().z + 4.0 + 1.5};
  sim.team_input(cab);
  const auto gap_m = [&] {  // the spreader's underside above the cab's roof
    return sim.machine().attachment_bottom_z_m() - (cab.pose.position.z + cab.half_extents_m.z);
  };
  const double gap_before = gap_m();
  scene::Controls c = sim.control_table().neutral();
  c.value[static_cast<std::size_t>(sim.control_table().find("hoist"))] = -1.0;
  double least_gap = 1e9;
  for (int k = 0; k < 12000; ++k) {
    sim.step(c);
    evaluator.observe(sim, c);
    least_gap = std::min(least_gap, gap_m());
  }
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
  std::printf(
      "the spreader lowered onto a tractor's cab: %.2f m above it before, %.3f m at least, %.3f m after "
      "12 s; %d collisions (%d vehicle), worst %.2f m/s\n",
      gap_before, least_gap, gap_m(), evaluator.metrics().collisions, evaluator.metrics().vehicle_collisions,
      evaluator.metrics().worst_collision_mps);
  EXPECT_NEAR(gap_before, 4.0, 0.05);
  EXPECT_GT(least_gap, -0.15);  // it came to rest on the roof, not through it
  EXPECT_LT(gap_m(), 0.5);
  EXPECT_GE(evaluator.metrics().vehicle_collisions, 1);
  EXPECT_GT(evaluator.metrics().worst_collision_mps, 0.5);
}

TEST(TeamObstacles, InputsOutOfRangeAreRefused) {
  const ExerciseSettings exercise =
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_free_practice.yaml");
  Simulation sim(exercise.scenario);
  TeamInput far;
  far.kind = TeamInput::Kind::kObstacleAt;
  far.slot = TeamObstacles::kMostObstacles;
  far.half_extents_m = {1, 1, 1};
  EXPECT_EQ(sim.why_refused(far), "an obstacle past 32");
  far.slot = 0;
  far.half_extents_m = {1, 30, 1};
  EXPECT_EQ(sim.why_refused(far), "an obstacle's side outside 0-50 m");
  far.half_extents_m = {1, std::nan(""), 1};
  EXPECT_EQ(sim.why_refused(far), "an obstacle's side outside 0-50 m");
  EXPECT_THROW(sim.team_input(far), std::invalid_argument);
  EXPECT_EQ(sim.obstacles().count(), 0);  // nothing made
  // a handed box's name: printable ASCII of at most 19 characters, NUL-padded
  TeamInput load;
  load.kind = TeamInput::Kind::kLoadOn;
  load.mass_kg = 20000.0;
  EXPECT_TRUE(load.name_item("TGHU1000012"));
  EXPECT_EQ(load.item_name(), "TGHU1000012");
  EXPECT_EQ(why_invalid(load), "");
  load.item[3] = '\n';
  EXPECT_EQ(why_invalid(load), "an item's name of other than printable ASCII");
  load.name_item("TGHU1000012");
  load.item[15] = 'X';  // after the name's end
  EXPECT_EQ(why_invalid(load), "an item's name of other than printable ASCII");
  EXPECT_FALSE(load.name_item("A NAME OF TWENTY CHARS"));
  EXPECT_EQ(load.item_name(), "");
}

}  // namespace
}  // namespace harbour::sim
