#include "harbour/bulk/HeightGrid.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

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
    active.relax_active();
    sweep.relax_full_sweep();
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
    grid.relax_active();
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
    grid.relax_active();
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
      grid.relax_active();
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

TEST(HeightGrid, PouredHeapIsRound) {
  HeightGrid grid({120, 120, 0.1}, scenes::test_material(35.0), {});
  scenes::pour_heap(grid, 20.0, 0.01);
  const HeapExtents e = heap_extents(grid, 0.01);
  EXPECT_NEAR(e.ratio(), 1.0, 0.10) << "axes " << e.along_axes_m << " m, diagonals " << e.along_diagonals_m
                                    << " m";
}

class AngleOfRepose : public ::testing::TestWithParam<double> {};

TEST_P(AngleOfRepose, PouredHeapSettlesAtTheMaterialAngle) {
  const double repose_deg = GetParam();
  HeightGrid grid({120, 120, 0.1}, scenes::test_material(repose_deg), {});
  scenes::pour_heap(grid, 25.0, 0.01);
  EXPECT_EQ(grid.active_count(), 0u) << "heap did not come to rest";
  EXPECT_NEAR(core::rad_to_deg(fitted_cone_angle(grid)), repose_deg, 1.5);
}

// grain, coal, gravel (data/materials.yaml)
INSTANTIATE_TEST_SUITE_P(Materials, AngleOfRepose, ::testing::Values(27.0, 35.0, 40.0));

}  // namespace
}  // namespace harbour::bulk
