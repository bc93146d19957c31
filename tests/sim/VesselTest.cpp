#include "harbour/sim/Vessel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/io/VesselFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/sim/Simulation.h"
#include "scenes/StsScenes.h"

namespace harbour::sim {
namespace {

VesselPlacement feeder() {
  VesselPlacement p;
  p.vessel = io::load_vessel(HARBOUR_DATA_DIR "/vessels/feeder_1100teu.yaml");
  p.keel_midship_m = {31.0, 0.0, -10.5};
  return p;
}

TEST(Vessel, SlotsFollowIsoBayRowTierNumbering) {
  const VesselGeometry g(feeder());
  std::string why;
  // rows 01, 03 ... to starboard (+x), 02, 04 ... to port, half a pitch either side of the centreline
  EXPECT_NEAR(*g.row_x(1), 1.27, 1e-12);
  EXPECT_NEAR(*g.row_x(2), -1.27, 1e-12);
  EXPECT_NEAR(*g.row_x(7), 3.5 * 2.54, 1e-12);
  EXPECT_FALSE(g.row_x(9).has_value());
  // hold tier 02 stands on the tank top, tier 04 on it; deck tier 82 on the hatch cover
  EXPECT_NEAR(g.slot_centre({12, 1, 2}, 2.591, why)->z, 1.5 + 2.591 / 2, 1e-12);
  EXPECT_NEAR(g.slot_centre({12, 1, 4}, 2.591, why)->z, 1.5 + 2.591 * 1.5, 1e-12);
  EXPECT_NEAR(g.slot_centre({12, 1, 82}, 2.591, why)->z, 11.5 + 1.5 + 0.8 + 2.591 / 2, 1e-12);
  EXPECT_NEAR(g.slot_centre({16, 1, 82}, 2.591, why)->y, 14.0, 1e-12);
  EXPECT_FALSE(g.slot_centre({12, 1, 10}, 2.591, why).has_value());  // only 4 hold tiers
  EXPECT_NE(why.find("tier 10"), std::string::npos);
}

TEST(Vessel, CellGuidesKeepAContainerInItsCell) {
  // a hold box pushed sideways hard stops at the guides: its clearance (25 mm) and no more
  ScenarioSettings s = scenes::sts_discharge(HARBOUR_DATA_DIR);
  ContainerPlacement box = s.containers[0];
  box.id = "HOLD";
  std::string why;
  const VesselGeometry g(*s.vessel);
  box.pose.position = g.pose_at(0).to_parent(*g.slot_centre({12, 3, 2}, 2.591, why));
  s.containers.insert(s.containers.begin(), box);
  Simulation sim(s);
  EXPECT_GT(sim.vessel()->cell_guide_shapes(), 3 * 8 * 8 - 1);  // 8 legs per cell, 8 rows, 3 bays
  sim.release(0);                                               // as if the spreader had lifted it
  physics::PhysicsWorld& world = const_cast<physics::PhysicsWorld&>(sim.world());
  const double x0 = world.pose(sim.container_body(0)).position.x;
  for (int k = 0; k < 2000; ++k) {
    world.add_force_at(sim.container_body(0), world.pose(sim.container_body(0)).position, {3e5, 0, 0});
    sim.step({});
  }
  const double moved = world.pose(sim.container_body(0)).position.x - x0;
  EXPECT_GT(moved, 0.015);
  EXPECT_LT(moved, 0.025 + 0.005);
}

TEST(Vessel, SecuredCargoRidesTheSeaState) {
  ScenarioSettings s = scenes::sts_discharge(HARBOUR_DATA_DIR);
  s.vessel->sea.heave_m = {{0.2, 8.0, 0.0}};
  s.vessel->sea.roll_rad = {{core::deg_to_rad(0.5), 12.0, 0.0}};
  Simulation sim(s);
  const std::size_t deck_box = 1;  // bay 12 row 01 tier 82
  const double z0 = sim.world().pose(sim.container_body(deck_box)).position.z;
  for (int k = 0; k < 2000; ++k)  // a quarter of the heave period: the crest
    sim.step({});
  const core::Pose vessel = sim.vessel()->geometry().pose_at(sim.time_s());
  std::string why;
  const core::Vec3 expected =
      vessel.to_parent(*sim.vessel()->geometry().slot_centre({12, 1, 82}, 2.591, why));
  const core::Vec3 at = sim.world().pose(sim.container_body(deck_box)).position;
  // the box is where the moving hull carries it, to a step of motion (heave 0.2 m, roll 0.5 deg)
  EXPECT_NEAR(at.x, expected.x, 1e-3);
  EXPECT_NEAR(at.z, expected.z, 1e-3);
  EXPECT_GT(at.z - z0, 0.15);
  EXPECT_TRUE(sim.world().is_kinematic(sim.container_body(deck_box)));
}

TEST(Trucks, ALoadedTruckLeavesAndTheNextDrivesIn) {
  ExerciseSettings e = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  e.scenario.trucks.trucks = 2;
  Simulation sim(e.scenario);
  GantryAutopilot pilot(e);
  while (!pilot.done() && sim.time_s() < 300.0)
    sim.step(pilot.next(sim));
  ASSERT_TRUE(pilot.done());
  for (int k = 0; k < 40000; ++k)
    sim.step(pilot.next(sim));
  EXPECT_EQ(sim.trucks()->departed(), 1);
  EXPECT_NEAR(sim.trucks()->truck_y(1), e.scenario.trucks.stop_y_m, 1e-6);  // the next one waits
  // the box went with its truck
  const double box_y = sim.world().pose(sim.container_body(1)).position.y;
  EXPECT_NEAR(box_y, sim.trucks()->truck_y(0), 0.05);
  EXPECT_GT(box_y, 50.0);
}

}  // namespace
}  // namespace harbour::sim
