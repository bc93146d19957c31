#include "harbour/sim/Simulation.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "scenes/StsScenes.h"

namespace harbour::sim {
namespace {

std::vector<std::uint64_t> hashes_per_second(double nudge = 0.0) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  std::vector<std::uint64_t> out;
  for (std::int64_t k = 0; k < 15000; ++k) {
    Inputs in = scenes::scripted_operator(k);
    if (k == 5000) in.sts.gantry += nudge;  // the gantry is idle then: any change moves it
    s.step(in);
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

// A lever beyond its travel reads as the end of it, a non-finite one (a device or link fault) as centred;
// the state stays finite either way.
TEST(Simulation, LeversOutOfRangeReadAsTheMachineWouldReadThem) {
  auto run = [](double trolley_lever, double hoist_lever) {
    Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
    Inputs in;
    in.sts.trolley = trolley_lever;
    in.sts.hoist = hoist_lever;
    in.sts.spreader_size_ft = 33;
    for (int k = 0; k < 2000; ++k)
      s.step(in);
    EXPECT_EQ(s.warnings().total(), 0u);
    return s.state_hash();
  };
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(run(7.5, 0.0), run(1.0, 0.0));
  EXPECT_EQ(run(nan, -inf), run(0.0, 0.0));
  EXPECT_NE(run(1.0, 0.0), run(0.0, 0.0));

  Inputs odd;
  odd.sts.gantry = nan;
  odd.sts.boom = -2.0;
  odd.sts.spreader_size_ft = 33;
  const Inputs read = in_range(odd);
  EXPECT_EQ(read.sts.gantry, 0.0);
  EXPECT_EQ(read.sts.boom, -1.0);
  EXPECT_EQ(read.sts.spreader_size_ft, 0);
}

TEST(Simulation, HoldFreezesAndSingleStepAdvances) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  for (std::int64_t k = 0; k < 2000; ++k)
    s.step(scenes::scripted_operator(k));
  s.hold();
  const std::uint64_t frozen = s.state_hash();
  for (int k = 0; k < 500; ++k)
    s.step(scenes::scripted_operator(2000));
  EXPECT_EQ(s.state_hash(), frozen);
  EXPECT_EQ(s.steps(), 2000);
  EXPECT_TRUE(s.snapshot().held);
  s.single_step(scenes::scripted_operator(2000));
  EXPECT_EQ(s.steps(), 2001);
  EXPECT_NE(s.state_hash(), frozen);
  s.resume();
  s.step(scenes::scripted_operator(2001));
  EXPECT_EQ(s.steps(), 2002);
}

TEST(Simulation, SnapshotShowsTheMachineAndTheContainers) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  for (std::int64_t k = 0; k < 3000; ++k)
    s.step(scenes::scripted_operator(k));
  const Snapshot snap = s.snapshot();
  EXPECT_EQ(snap.step, 3000);
  EXPECT_DOUBLE_EQ(snap.time_s, 3.0);
  EXPECT_GT(snap.trolley_x_m, 32.27);          // moved waterside
  ASSERT_EQ(snap.containers.size(), 3u + 6u);  // and the hatch covers of three bays
  EXPECT_EQ(snap.containers[1].id, "TGHU1000012");
  // on the hatch cover: keel -10.5 + depth 11.5 + coaming 1.5 + cover 0.8
  EXPECT_NEAR(snap.containers[1].pose.position.z, 3.3 + 2.591 / 2, 0.01);
  EXPECT_EQ(snap.containers[3].id, "HATCH8P");
  EXPECT_GT(snap.hoisted_load_n, 0.9 * 15000 * 9.80665);  // the spreader hangs
}

}  // namespace
}  // namespace harbour::sim
