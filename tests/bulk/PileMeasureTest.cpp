#include "harbour/bulk/PileMeasure.h"

#include <gtest/gtest.h>

#include <cmath>

#include "harbour/core/Units.h"
#include "scenes/BulkScenes.h"

namespace harbour::bulk {
namespace {

// an exact cone of slope 30 degrees, built cell by cell
HeightGrid cone(double slope_deg) {
  HeightGrid g({101, 101, 0.1}, scenes::test_material(), {});
  const double t = std::tan(core::deg_to_rad(slope_deg));
  for (int j = 0; j < 101; ++j)
    for (int i = 0; i < 101; ++i) {
      const double r = 0.1 * std::hypot(i - 50, j - 50);
      if (r < 4.0) g.add_volume(i, j, (4.0 - r) * t * g.cell_area_m2());
    }
  return g;
}

TEST(PileMeasure, FittedConeAngleOfAnExactCone) {
  EXPECT_NEAR(core::rad_to_deg(fitted_cone_angle(cone(30.0))), 30.0, 0.05);
}

TEST(PileMeasure, MedianFlankAngleOfAnExactCone) {
  EXPECT_NEAR(core::rad_to_deg(median_flank_angle(cone(30.0), core::deg_to_rad(5.0))), 30.0, 0.2);
}

TEST(PileMeasure, ConeIsRoundAndADiamondIsNot) {
  EXPECT_NEAR(heap_extents(cone(30.0), 0.01).ratio(), 1.0, 0.03);
  HeightGrid diamond({101, 101, 0.1}, scenes::test_material(), {});
  for (int j = 0; j < 101; ++j)
    for (int i = 0; i < 101; ++i) {
      const double r1 = 0.1 * (std::abs(i - 50) + std::abs(j - 50));  // L1 distance: the 4-neighbour heap
      if (r1 < 4.0) diamond.add_volume(i, j, (4.0 - r1) * diamond.cell_area_m2());
    }
  EXPECT_NEAR(heap_extents(diamond, 0.01).ratio(), 1.0 / std::sqrt(2.0), 0.03);
}

}  // namespace
}  // namespace harbour::bulk
