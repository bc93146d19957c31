#include "harbour/machines/parts/OdeCableBodies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "harbour/cable/HoistSystem.h"
#include "harbour/io/ReevingFiles.h"

namespace harbour::sim {
namespace {

constexpr double kDt = 0.001;
constexpr double kG = 9.80665;

// The STS hoist from data/reeving on ODE bodies: a trolley locked on its rail (slider motor at zero speed), a
// headblock with spreader and container (80 t) on 8 parts. Swinging across the trolley's travel, the 4 ropes
// form parallelograms: the load is a simple pendulum of the fall length.
TEST(OdeCableBodies, StsLoadSwingsWithThePendulumPeriod) {
  physics::PhysicsWorld world({});
  physics::BoxSettings trolley;
  trolley.mass_kg = 30000;
  trolley.half_extents_m = {3, 2, 1};
  trolley.pose.position = {20, 0, 49};
  trolley.collides = false;
  physics::BoxSettings headblock;
  headblock.mass_kg = 80000;
  headblock.half_extents_m = {6.1, 1.2, 1.3};  // a 40 ft container under its spreader
  headblock.pose.position = {20, 0.3, 20};     // 0.3 m across: 0.6 degrees
  headblock.collides = false;
  const physics::BodyId t = world.add_box(trolley);
  const physics::BodyId h = world.add_box(headblock);
  const auto rail = world.add_slider(physics::kWorld, t, {1, 0, 0});
  world.set_slider_motor(rail, 0.0, 1e7);

  const io::ReevingFile file = io::load_reeving(HARBOUR_DATA_DIR "/reeving/sts_hoist.yaml");
  OdeCableBodies bodies(world, {physics::kWorld, t, h});  // the gantry stands still: the world
  cable::HoistSystem hoist(file.reeving, bodies, {0, 0, -kG});
  const std::vector<cable::DrumCommand> brake(1);

  auto step = [&] {
    hoist.step(kDt, brake, bodies);
    world.step(kDt);
  };
  for (int k = 0; k < 3000; ++k)
    step();  // the axial bounce dies
  std::vector<double> y;
  double fall = 0.0;
  const int n = 60000;
  for (int k = 0; k < n; ++k) {
    step();
    y.push_back(world.pose(h).position.y);
    fall += (world.point_position(t, {0, 0, -1.0}).z - world.point_position(h, {0, 0, 0.5}).z) / n;
  }
  double mean = 0;
  for (double v : y)
    mean += v / n;
  std::vector<double> crossings;
  for (std::size_t k = 1; k < y.size(); ++k)
    if (y[k - 1] < mean && y[k] >= mean)
      crossings.push_back(static_cast<double>(k) - (y[k] - mean) / (y[k] - y[k - 1]));
  ASSERT_GE(crossings.size(), 4u);
  const double period =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1) * kDt;
  const double expected = 2 * std::numbers::pi * std::sqrt(fall / kG);
  EXPECT_NEAR(period, expected, 0.01 * expected) << "fall " << fall << " m";
  for (int r = 0; r < hoist.rope_count(); ++r)
    EXPECT_TRUE(hoist.oscillating(r, 2));
}

}  // namespace
}  // namespace harbour::sim
