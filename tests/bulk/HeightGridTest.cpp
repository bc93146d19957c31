#include "harbour/bulk/HeightGrid.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <vector>

#include "harbour/bulk/PileMeasure.h"
#include "harbour/core/Rng.h"
#include "harbour/core/Units.h"
#include "scenes/BulkScenes.h"

namespace harbour::bulk {
namespace {

constexpr GridSettings kSmall{64, 64, 0.1};

bool bit_identical(const HeightGrid& a, const HeightGrid& b) {
  for (int j = 0; j < a.cells_y(); ++j)
    for (int i = 0; i < a.cells_x(); ++i)
      if (std::bit_cast<std::uint64_t>(a.height(i, j)) != std::bit_cast<std::uint64_t>(b.height(i, j)))
        return false;
  return true;
}

// random pours, digs and presses applied identically to both grids
void disturb(core::Rng& rng, HeightGrid& a, HeightGrid& b) {
  const int i = static_cast<int>(rng.below(64)), j = static_cast<int>(rng.below(64));
  switch (rng.below(3)) {
    case 0: {
      const double v = rng.uniform(0.0, 0.05);
      a.add_volume(i, j, v);
      b.add_volume(i, j, v);
      break;
    }
    case 1: {
      const double t = rng.uniform(0.0, 0.5);
      a.remove_layer(i, j, t);
      b.remove_layer(i, j, t);
      break;
    }
    default: {
      const double c = rng.below(2) ? rng.uniform(0.0, 0.3) : 0.0;
      a.set_compression(i, j, c);
      b.set_compression(i, j, c);
    }
  }
}

void expect_active_equals_sweep(bool rolling) {
  const Material m = scenes::test_material();
  HeightGrid active(kSmall, m, {}), sweep(kSmall, m, {});
  core::Rng rng(2024);
  std::size_t examined_active = 0, examined_sweep = 0;
  for (int step = 0; step < 3000; ++step) {
    if (step % 5 == 0) disturb(rng, active, sweep);
    if (rolling) {
      core::Pose pose;
      pose.rotation = core::Mat3::rotation({1, 0, 0}, core::deg_to_rad(6.0) * std::sin(step * 0.004));
      active.set_pose(pose);
      sweep.set_pose(pose);
    }
    active.relax_active(0.001);
    sweep.relax_full_sweep(0.001);
    examined_active += active.examined_count();
    examined_sweep += sweep.examined_count();
    ASSERT_TRUE(bit_identical(active, sweep)) << "diverged at step " << step;
  }
  EXPECT_LT(examined_active, examined_sweep);  // the list must skip work even in this busy scene
}

TEST(HeightGrid, ActiveListMatchesFullSweepBitForBit) {
  expect_active_equals_sweep(false);
}

TEST(HeightGrid, ActiveListMatchesFullSweepOnARollingGrid) {
  expect_active_equals_sweep(true);
}

TEST(HeightGrid, RelaxationConservesVolumeAndNeverGoesNegative) {
  HeightGrid grid(kSmall, scenes::test_material(30.0, 0.9), {});
  grid.add_volume(32, 32, 5.0);  // a 500 m column on one cell: violent avalanche
  const double before = grid.total_volume_m3();
  for (int n = 0; n < 2000; ++n)
    grid.relax_active(0.001);
  EXPECT_NEAR(grid.total_volume_m3(), before, 1e-12 * before);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      ASSERT_GE(grid.height(i, j), 0.0);
}

TEST(HeightGrid, StableSlopeDoesNotMove) {
  // a ramp 2 degrees below the angle of repose stays exactly as built
  HeightGrid grid(kSmall, scenes::test_material(35.0), {});
  const double slope = std::tan(core::deg_to_rad(33.0));
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      grid.add_volume(i, j, (64 - i) * 0.1 * slope * grid.cell_area_m2());
  const double h = grid.height(10, 10);
  for (int n = 0; n < 50; ++n)
    grid.relax_active(0.001);
  EXPECT_EQ(grid.height(10, 10), h);
  EXPECT_EQ(grid.active_count(), 0u);
}

// a layer in a hold tilted by phi about x: below the angle of repose nothing moves; beyond it the
// surface settles at the repose angle in the world, i.e. at phi - repose against the hold floor
TEST(HeightGrid, TiltedLayerSettlesAtTheReposeAngleInTheWorld) {
  const Material m = scenes::test_material(30.0);
  for (const double tilt_deg : {25.0, 40.0}) {
    HeightGrid grid({16, 64, 0.1}, m, {});
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 16; ++i)
        grid.add_volume(i, j, 1.0 * grid.cell_area_m2());  // 1 m layer
    core::Pose pose;
    pose.rotation = core::Mat3::rotation({1, 0, 0}, core::deg_to_rad(tilt_deg));  // +y side rises
    grid.set_pose(pose);
    for (int n = 0; n < 200000 && grid.active_count() > 0; ++n)
      grid.relax_active(0.001);
    ASSERT_EQ(grid.active_count(), 0u);
    // least-squares slope of the surface along y in the middle column, away from the walls
    double sy = 0, sh = 0, syy = 0, syh = 0, n = 0;
    for (int j = 8; j < 56; ++j) {
      const double y = j * 0.1, h = grid.height(8, j);
      sy += y, sh += h, syy += y * y, syh += y * h, n += 1;
    }
    const double slope_deg = core::rad_to_deg(std::atan(-(n * syh - sy * sh) / (n * syy - sy * sy)));
    const double expected_deg = tilt_deg < 30.0 ? 0.0 : tilt_deg - 30.0;
    EXPECT_NEAR(slope_deg, expected_deg, 0.5) << "tilt " << tilt_deg;
  }
}

// A slow pour: 0.05 m^3/s onto one 10 cm cell (2 m^3 in 40 s), slow enough that no avalanche gathers the
// momentum to run past the repose angle.
constexpr double kSlowPour_m3_per_step = 0.00005;

TEST(HeightGrid, PouredHeapIsRound) {
  HeightGrid grid({120, 120, 0.1}, scenes::test_material(35.0), {});
  scenes::pour_heap(grid, 2.0, kSlowPour_m3_per_step);
  const HeapExtents e = heap_extents(grid, 0.01);
  EXPECT_NEAR(e.ratio(), 1.0, 0.03) << "axes " << e.along_axes_m << " m, diagonals " << e.along_diagonals_m
                                    << " m";
}

class AngleOfRepose : public ::testing::TestWithParam<double> {};

TEST_P(AngleOfRepose, PouredHeapSettlesAtTheMaterialAngle) {
  const double repose_deg = GetParam();
  HeightGrid grid({120, 120, 0.1}, scenes::test_material(repose_deg), {});
  scenes::pour_heap(grid, 2.0, kSlowPour_m3_per_step);
  EXPECT_EQ(grid.active_count(), 0u) << "heap did not come to rest";
  EXPECT_NEAR(core::rad_to_deg(fitted_cone_angle(grid)), repose_deg, 0.5);
}

// grain, coal, gravel (data/materials.yaml)
INSTANTIATE_TEST_SUITE_P(Materials, AngleOfRepose, ::testing::Values(27.0, 35.0, 40.0));

// A granular column (aspect 2) released on a floor comes to rest within 10 sqrt(H/g) of simulated time, the
// same time within 20 % at 10, 5 and 2.5 cm cells (the flow's speed is physical, not so many cells a step).
TEST(Flow, AColumnCollapsesInAFewFreeFallTimesWhateverTheCellSize) {
  const double radius = 0.8, height = 1.6;
  std::vector<double> times;
  for (const double cell : {0.1, 0.05, 0.025}) {
    const scenes::ColumnCollapse c = scenes::collapse_column(radius, height / radius, cell, 30.0, 34.0, 4.0);
    ASSERT_TRUE(c.at_rest) << cell;
    EXPECT_NEAR(c.volume_after_m3, c.volume_m3, 1e-12 * c.volume_m3);
    std::printf("cells %.3f m: at rest after %.3f s = %.2f sqrt(H/g), runout (R-r)/r %.2f\n", cell,
                c.time_to_rest_s, c.time_to_rest_s / std::sqrt(height / 9.81),
                (c.runout_m - radius) / radius);
    EXPECT_LT(c.time_to_rest_s, 10.0 * std::sqrt(height / 9.81)) << cell;
    EXPECT_GT(c.time_to_rest_s, 1.0 * std::sqrt(height / 9.81)) << cell;  // not instantly either
    times.push_back(c.time_to_rest_s);
  }
  const double mean = (times[0] + times[1] + times[2]) / 3.0;
  for (const double t : times)
    EXPECT_NEAR(t, mean, 0.2 * mean);
}

// Runout of axisymmetric column collapses against the laboratory law of Lube et al. (2004, JFM 508):
// (R - r) / r = 1.24 a for a < 1.7, 1.6 a^1/2 above, within 25 %, at four aspect ratios a.
TEST(Flow, RunoutFollowsTheLaboratoryLawAtFourAspectRatios) {
  for (const double a : {0.5, 1.0, 2.0, 4.0}) {
    const scenes::ColumnCollapse c = scenes::collapse_column(1.6, a, 0.1, 30.0, 34.0, 5.0);
    ASSERT_TRUE(c.at_rest) << a;
    const double runout = (c.runout_m - 1.6) / 1.6, lab = a < 1.7 ? 1.24 * a : 1.6 * std::sqrt(a);
    std::printf("a %.1f: runout %.2f, laboratory %.2f (%.0f %%)\n", a, runout, lab, 100.0 * runout / lab);
    EXPECT_NEAR(runout, lab, 0.25 * lab) << "aspect ratio " << a;
  }
}

// 12 m^3 dumped in a second onto the top of a heap spreads within a few seconds: at rest, no slope steeper
// than the repose angle's, the top no higher than the cone of the whole volume at that angle. (The dump also
// carries part of the old heap's top with it: a depth-averaged flow moves whole columns —
// docs/models/bulk.md.)
TEST(Flow, AGrabDumpOnAHeapSpreadsWithinSeconds) {
  const Material m = scenes::test_material(35.0);
  HeightGrid grid({200, 200, 0.1}, m, {});
  const double c = 10.0, t = std::tan(m.angle_of_repose_rad);
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 200; ++i) {
      const double r = std::hypot((i + 0.5) * 0.1 - c, (j + 0.5) * 0.1 - c);
      if (r < 4.0) grid.add_volume(i, j, (4.0 - r) * t * grid.cell_area_m2());
    }
  for (int n = 0; n < 20000 && grid.active_count() > 0; ++n)
    grid.relax_active(0.001);
  ASSERT_EQ(grid.active_count(), 0u);
  const double before = grid.total_volume_m3();
  int steps = 0;
  for (; steps < 1000; ++steps) {  // the grab's 12 m^3 through a 1.2 m x 1.2 m opening over 1 s
    for (int j = 94; j < 106; ++j)
      for (int i = 94; i < 106; ++i)
        grid.add_volume(i, j, 12.0 / 144.0 / 1000.0);
    grid.relax_active(0.001);
  }
  for (; steps < 60000 && grid.active_count() > 0; ++steps)
    grid.relax_active(0.001);
  EXPECT_EQ(grid.active_count(), 0u);
  const double seconds = steps * 0.001;
  std::printf("the dump at rest %.2f s after it began\n", seconds);
  EXPECT_LT(seconds, 10.0);
  EXPECT_NEAR(grid.total_volume_m3(), before + 12.0, 1e-9);
  const double cone_top =
      std::cbrt(3.0 * (before + 12.0) / (std::numbers::pi * t)) * t;  // V = pi r^3 tan / 3
  EXPECT_LT(grid.max_height_m(), 1.02 * cone_top);
  std::printf("top %.2f m, the cone of the whole volume at the repose angle %.2f m\n", grid.max_height_m(),
              cone_top);
  double steepest = 0.0;
  for (int j = 0; j + 1 < 200; ++j)
    for (int i = 0; i + 1 < 200; ++i)
      steepest = std::max({steepest, std::abs(grid.height(i + 1, j) - grid.height(i, j)) / 0.1,
                           std::abs(grid.height(i, j + 1) - grid.height(i, j)) / 0.1});
  EXPECT_LT(steepest, t + 1e-3);  // settled: nowhere steeper than the repose angle
}

}  // namespace
}  // namespace harbour::bulk
