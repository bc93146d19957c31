#include "harbour/sim/Simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "scenes/StsScenes.h"

#include "harbour/machines/sts/StsCrane.h"

namespace harbour::sim {
namespace {

std::vector<std::uint64_t> hashes_per_second(double nudge = 0.0) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  std::vector<std::uint64_t> out;
  for (std::int64_t k = 0; k < 15000; ++k) {
    StsControls in = scenes::scripted_operator(k);
    if (k == 5000) in.gantry += nudge;  // the gantry is idle then: any change moves it
    s.step(scenes::cab(in));
    if (s.steps() % 1000 == 0) out.push_back(s.state_hash());
  }
  EXPECT_EQ(s.warnings().total(), 0u);
  return out;
}

TEST(Simulation, SameInputsGiveTheSameStateHashEverySecond) {
  const auto a = hashes_per_second(), b = hashes_per_second();
  EXPECT_EQ(a, b);
  const auto c = hashes_per_second(1e-9);  // one lever differs by 1e-9 for one millisecond
  EXPECT_EQ(std::vector(a.begin(), a.begin() + 5), std::vector(c.begin(), c.begin() + 5));
  EXPECT_NE(a.back(), c.back());
}

// The state hash checks everything the machine saves: the RTG's horn (saved in its keyframes, left out of
// its hand-picked hash) held for one step tells two runs apart; as runs recorded before were checked, it
// does not.
TEST(Simulation, TheStateHashChecksEverythingTheMachineSaves) {
  for (const bool by_hand : {false, true}) {
    ScenarioSettings scenario = io::load_exercise(HARBOUR_DATA_DIR "/exercises/rtg_rehandle.yaml").scenario;
    scenario.machine_hashed_by_hand = by_hand;
    Simulation quiet(scenario), horn(scenario);
    const scene::Controls neutral = quiet.control_table().neutral();
    scene::Controls sounding = neutral;
    sounding.value[static_cast<std::size_t>(horn.control_table().find("horn"))] = 1.0;
    for (int k = 0; k < 100; ++k) {
      quiet.step(neutral);
      horn.step(k == 99 ? sounding : neutral);
    }
    EXPECT_EQ(quiet.world().state_hash(), horn.world().state_hash()) << "the horn moves nothing";
    if (by_hand) {
      EXPECT_EQ(quiet.state_hash(), horn.state_hash());
    } else {
      EXPECT_NE(quiet.state_hash(), horn.state_hash());
    }
  }
}

// A lever beyond its travel reads as the end of it, a non-finite one (a device or link fault) as centred;
// the state stays finite either way.
TEST(Simulation, LeversOutOfRangeReadAsTheMachineWouldReadThem) {
  auto run = [](double trolley_lever, double hoist_lever) {
    Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
    StsControls in;
    in.trolley = trolley_lever;
    in.hoist = hoist_lever;
    in.spreader_size_ft = 33;
    for (int k = 0; k < 2000; ++k)
      s.step(scenes::cab(in));
    EXPECT_EQ(s.warnings().total(), 0u);
    return s.state_hash();
  };
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(run(7.5, 0.0), run(1.0, 0.0));
  EXPECT_EQ(run(nan, -inf), run(0.0, 0.0));
  EXPECT_NE(run(1.0, 0.0), run(0.0, 0.0));

  // the table reads a control as the machine will: levers clamped, a non-finite value neutral, a button 0/1,
  // a switch at a whole position
  const scene::ControlTable table = scenes::sts_controls();
  scene::Controls odd = table.neutral();
  odd.value[static_cast<std::size_t>(table.find("gantry"))] = nan;
  odd.value[static_cast<std::size_t>(table.find("boom"))] = -2.0;
  odd.value[static_cast<std::size_t>(table.find("horn"))] = 7.0;
  odd.value[static_cast<std::size_t>(table.find("flipper_2"))] = 0.7;
  odd.value[static_cast<std::size_t>(table.find("flipper_3"))] = 9.0;
  const scene::Controls read = table.in_range(odd);
  EXPECT_EQ(read.value[static_cast<std::size_t>(table.find("gantry"))], 0.0);
  EXPECT_EQ(read.value[static_cast<std::size_t>(table.find("boom"))], -1.0);
  EXPECT_EQ(read.value[static_cast<std::size_t>(table.find("horn"))], 1.0);
  EXPECT_EQ(read.value[static_cast<std::size_t>(table.find("flipper_2"))], 1.0);
  EXPECT_EQ(read.value[static_cast<std::size_t>(table.find("flipper_3"))], 1.0);
  // two size buttons at once select no size
  StsControls both;
  both.spreader_size_ft = 20;
  scene::Controls two = scenes::cab(both);
  two.value[static_cast<std::size_t>(table.find("spreader_40"))] = 1.0;
  EXPECT_EQ(StsControlSlots(table).read(two).spreader_size_ft, 0);
  EXPECT_EQ(StsControlSlots(table).read(scenes::cab(both)).spreader_size_ft, 20);
}

TEST(Simulation, HoldFreezesAndSingleStepAdvances) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  for (std::int64_t k = 0; k < 2000; ++k)
    s.step(scenes::cab(scenes::scripted_operator(k)));
  s.hold();
  const std::uint64_t frozen = s.state_hash();
  for (int k = 0; k < 500; ++k)
    s.step(scenes::cab(scenes::scripted_operator(2000)));
  EXPECT_EQ(s.state_hash(), frozen);
  EXPECT_EQ(s.steps(), 2000);
  EXPECT_TRUE(s.snapshot()->held);
  s.single_step(scenes::cab(scenes::scripted_operator(2000)));
  EXPECT_EQ(s.steps(), 2001);
  EXPECT_NE(s.state_hash(), frozen);
  s.resume();
  s.step(scenes::cab(scenes::scripted_operator(2001)));
  EXPECT_EQ(s.steps(), 2002);
}

// The instructor's emergency stop holds the machine's own stop pressed: the trolley, driven at full lever,
// brakes on its emergency ramp (v^2 / 2a) and stays stopped; the trainee's controls are left as they were;
// the stop survives a keyframe; released, the lever drives it again.
TEST(Simulation, TheInstructorsEmergencyStopBrakesTheMachineUntilReleased) {
  const ScenarioSettings scenario = scenes::sts_discharge(HARBOUR_DATA_DIR);
  Simulation s(scenario);
  const auto& names = s.scene().indicators;
  const auto slot =
      static_cast<std::size_t>(std::find(names.begin(), names.end(), "trolley_x_m") - names.begin());
  ASSERT_LT(slot, names.size());
  auto trolley_x = [&] { return s.snapshot()->indicators[slot]; };
  StsControls in;
  in.trolley = -1.0;  // landward, full lever
  in.spreader_size_ft = 40;
  for (int k = 0; k < 6000; ++k)
    s.step(scenes::cab(in));
  const double before = trolley_x();
  s.step(scenes::cab(in));
  const double speed = (trolley_x() - before) / Simulation::kStep_s;
  ASSERT_GT(std::abs(speed), 1.0) << "the trolley runs at full lever";

  s.command({InstructorCommand::Kind::kEmergencyStop});
  const double at_stop = trolley_x();
  for (int k = 0; k < 8000; ++k)
    s.step(scenes::cab(in));  // the trainee still pushes the lever
  const double stopped_at = trolley_x();
  const double ramp = scenario.machine.as<StsSetup>().crane.trolley_drive.emergency_deceleration_mps2;
  const double expected = speed * speed / (2.0 * ramp);
  std::printf("trolley at %.2f m/s stops in %.3f m on its %.2f m/s^2 emergency ramp (v^2/2a = %.3f m)\n",
              std::abs(speed), std::abs(stopped_at - at_stop), ramp, expected);
  EXPECT_NEAR(std::abs(stopped_at - at_stop), expected, 0.15 * expected + 0.05)
      << "stopping distance at " << speed << " m/s on a " << ramp << " m/s^2 ramp";

  // a keyframe holds the stop
  Simulation copy(scenario);
  copy.restore_state(s.save_state());
  EXPECT_EQ(copy.state_hash(), s.state_hash());
  for (int k = 0; k < 1000; ++k) {
    s.step(scenes::cab(in));
    copy.step(scenes::cab(in));
  }
  EXPECT_EQ(copy.state_hash(), s.state_hash());
  EXPECT_NEAR(trolley_x(), stopped_at, 1e-3) << "it stays stopped";

  s.command({InstructorCommand::Kind::kReleaseEmergencyStop});
  for (int k = 0; k < 3000; ++k)
    s.step(scenes::cab(in));
  EXPECT_GT(std::abs(trolley_x() - stopped_at), 1.0) << "released, the lever drives it again";
  EXPECT_EQ(s.warnings().total(), 0u);
}

TEST(Simulation, SnapshotShowsTheMachineAndTheContainers) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  for (std::int64_t k = 0; k < 3000; ++k)
    s.step(scenes::cab(scenes::scripted_operator(k)));
  const scene::Snapshot snap = *s.snapshot();
  const scene::SceneDescription scene = s.scene();
  EXPECT_EQ(snap.version, scene::kSnapshotVersion);
  EXPECT_EQ(snap.step, 3000);
  EXPECT_DOUBLE_EQ(snap.time_s, 3.0);
  const auto indicator = [&](const std::string& name) {
    for (std::size_t n = 0; n < scene.indicators.size(); ++n)
      if (scene.indicators[n] == name) return snap.indicators[n];
    ADD_FAILURE() << "no indicator " << name;
    return 0.0;
  };
  EXPECT_EQ(snap.indicator_count, static_cast<int>(scene.indicators.size()));
  EXPECT_GT(indicator("trolley_x_m"), 32.27);  // moved waterside
  EXPECT_GT(indicator("load_t"), 0.9 * 15.0);  // the spreader hangs
  // gantry, trolley, spreader, vessel, a truck, 3 boxes and the hatch covers of three bays
  ASSERT_EQ(snap.entity_count, static_cast<int>(scene.entities.size()));
  ASSERT_EQ(scene.entities.size(), 5u + 3u + 6u);
  EXPECT_EQ(scene.entities[6].name, "TGHU1000012");
  EXPECT_EQ(scene.entities[6].visual, "container.40ft");
  // on the hatch cover: keel -10.5 + depth 11.5 + coaming 1.5 + cover 0.8
  EXPECT_NEAR(snap.entities[6].pose.position.z, 3.3 + 2.591 / 2, 0.01);
  EXPECT_EQ(scene.entities[8].name, "HATCH8P");
  EXPECT_EQ(scene.entities[8].visual, "hatch_cover");
  EXPECT_NEAR(snap.entities[2].pose.position.z, s.machine_as<StsCrane>().spreader_pose().position.z, 0.0);
  // the four hoist ropes, each a polyline from the drum over the trolley down to the headblock and back
  EXPECT_EQ(snap.rope_count, 4);
  for (int r = 0; r < snap.rope_count; ++r)
    EXPECT_GE(snap.rope_points[static_cast<std::size_t>(r)], 3);
  // at rest in the cab the operator's head feels 1 g up
  EXPECT_NEAR(snap.cab.specific_force_mps2.z, 9.80665, 0.5);
}

}  // namespace
}  // namespace harbour::sim
