// The reach stacker's stability: its load chart from the statics of its support, and that statics against the
// multibody model tipping it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>

#include "harbour/io/MachineFiles.h"
#include "harbour/machines/reach_stacker/ReachStackerStability.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665, kDt = 0.001;

ReachStackerSettings shipped() {
  return io::load_reach_stacker(HARBOUR_DATA_DIR "/machines/reach_stacker.yaml");
}

TEST(ReachStacker, ItsLoadChartGivesThePublishedRowRatings) {
  // published for the class: 45 t in the 1st row, 29 t in the 2nd, 15 t in the 3rd
  const ReachStackerSettings s = shipped();
  ASSERT_EQ(s.row_reach_m.size(), 3u);
  const double published_t[] = {45.0, 29.0, 15.0};
  for (std::size_t row = 0; row < 3; ++row) {
    const double rated_t = rated_load_kg(s, s.row_reach_m[row]) / 1000.0;
    EXPECT_NEAR(rated_t, published_t[row], 0.03 * published_t[row]) << "row " << row + 1;
    std::printf("row %zu at %.2f m: rated %.1f t (published %.0f t), tipping at %.1f t\n", row + 1,
                s.row_reach_m[row], rated_t, published_t[row],
                tipping_load_kg(s, s.row_reach_m[row]) / 1000.0);
  }
  // the 1st row is the structure's rating, not its stability's
  EXPECT_GT(tipping_load_kg(s, s.row_reach_m[0]) / s.stability_margin, s.rated_limit_kg);
  // the indicator: at the chart 1, warning from 0.9
  EXPECT_NEAR(load_moment_share(s, s.row_reach_m[1], rated_load_kg(s, s.row_reach_m[1])), 1.0, 1e-12);
  EXPECT_LT(load_moment_share(s, s.row_reach_m[2], 13000.0), s.warn_from);
  EXPECT_GT(load_moment_share(s, s.row_reach_m[2], 14000.0), s.warn_from);
}

// The shipped machine on its tyres (ODE body, the shared wheeled chassis, brakes on), the boom's and
// spreader's weights on it where the statics puts them, and a load at the boom's head `reach_m` ahead of the
// front axle growing at `rate_kg_s`: the load at which the rear axle's tyres leave the ground.
double load_lifting_the_rear_axle_kg(const ReachStackerSettings& s, double reach_m, double rate_kg_s) {
  physics::WorldSettings settings;
  physics::PhysicsWorld world(settings);
  physics::BoxSettings box;
  box.mass_kg = s.mass_kg;
  box.half_extents_m = s.half_extents_m;
  box.collides = false;
  box.pose.position = {0, 0, s.chassis.tyre.radius_m - s.chassis.axles.front().hub_z_m};
  const physics::BodyId body = world.add_box(box);
  WheeledChassis chassis(s.chassis, body);
  const double front = tipping_axle_x_m(s);
  const AxleSettings* rear = &s.chassis.axles.front();
  for (const AxleSettings& a : s.chassis.axles)
    if (a.x_m < rear->x_m) rear = &a;
  const core::Vec3 head{front + reach_m, 0.0, 3.0}, boom_centre = (s.boom_pivot_m + head) * 0.5;
  // settle with the boom and spreader on, then load it
  double load_kg = 0.0;
  for (int k = 0; k < 600000; ++k) {
    const double t = k * kDt;
    if (t > 3.0) load_kg += rate_kg_s * kDt;
    const core::Pose pose = world.pose(body);
    chassis.step(world, {0.0, false, 1.0, 0.0}, FlatGround());
    world.add_force_at(body, pose.to_parent(boom_centre), {0, 0, -s.boom_mass_kg * kG});
    world.add_force_at(body, pose.to_parent(head), {0, 0, -(s.spreader_mass_kg + load_kg) * kG});
    world.step(kDt);
    const core::Pose now = world.pose(body);
    const bool lifted = now.to_parent({rear->x_m, 0.0, rear->hub_z_m}).z - s.chassis.tyre.radius_m > 0.0;
    if (lifted) return load_kg;
  }
  return -1.0;
}

TEST(ReachStacker, TheMultibodyModelTipsAtTheStaticsThreshold) {
  // the load growing slowly (0.5 t/s, quasi-static) until the steer axle lifts: the statics of the support
  // polygon's front edge within 5 %
  const ReachStackerSettings s = shipped();
  for (const double reach : {s.row_reach_m[1], s.row_reach_m[2]}) {
    const double statics = tipping_load_kg(s, reach);
    const double multibody = load_lifting_the_rear_axle_kg(s, reach, 500.0);
    EXPECT_NEAR(multibody, statics, 0.05 * statics) << "at " << reach << " m";
    std::printf("at %.2f m: the steer axle lifts at %.2f t, statics %.2f t\n", reach, multibody / 1000.0,
                statics / 1000.0);
  }
}

TEST(ReachStacker, BadFilesNameTheField) {
  const auto error = [](const std::string& from, const std::string& to) {
    std::string text;
    {
      std::ifstream in(HARBOUR_DATA_DIR "/machines/reach_stacker.yaml");
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    try {
      io::load_reach_stacker(io::YamlFile::parse(text, "reach_stacker.yaml"));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  EXPECT_EQ(error("name: drg450_class", "name: drg450_class"), "loaded");
  std::string e = error("row_reach_m: [2.57, 5.42, 8.27]", "row_reach_m: [2.57, 8.27, 5.42]");
  EXPECT_NE(e.find("machine.load_chart.row_reach_m[2]"), std::string::npos) << e;
  EXPECT_NE(e.find("further out"), std::string::npos) << e;
  e = error("mass_kg: 47700", "mass_kg: 4770");
  EXPECT_NE(e.find("tips over with nothing on it"), std::string::npos) << e;
  e = error("stability_margin: 1.29", "stability_margin: 0.9");
  EXPECT_NE(e.find("machine.load_chart.stability_margin"), std::string::npos) << e;
}

}  // namespace
}  // namespace harbour::sim
