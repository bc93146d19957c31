#include "harbour/bulk/PileMeasure.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace harbour::bulk {

CellIndex highest_cell(const HeightGrid& grid) {
  CellIndex best;
  double top = -1.0;
  for (int j = 0; j < grid.cells_y(); ++j)
    for (int i = 0; i < grid.cells_x(); ++i)
      if (grid.height(i, j) > top) {
        top = grid.height(i, j);
        best = {i, j};
      }
  return best;
}

double fitted_cone_angle(const HeightGrid& grid) {
  const CellIndex peak = highest_cell(grid);
  const double top = grid.height(peak.i, peak.j);
  double sr = 0, sh = 0, srr = 0, srh = 0, n = 0;
  for (int j = 0; j < grid.cells_y(); ++j)
    for (int i = 0; i < grid.cells_x(); ++i) {
      const double h = grid.height(i, j);
      if (h < 0.15 * top || h > 0.85 * top) continue;
      const double r = grid.cell_size_m() * std::hypot(i - peak.i, j - peak.j);
      sr += r;
      sh += h;
      srr += r * r;
      srh += r * h;
      n += 1;
    }
  if (n < 3) return 0.0;
  const double slope = (n * srh - sr * sh) / (n * srr - sr * sr);
  return std::atan(-slope);
}

double median_flank_angle(const HeightGrid& grid, double min_angle_rad) {
  std::vector<double> angles;
  const double two_cells = 2.0 * grid.cell_size_m();
  for (int j = 1; j + 1 < grid.cells_y(); ++j)
    for (int i = 1; i + 1 < grid.cells_x(); ++i) {
      if (grid.height(i, j) <= 0.0) continue;
      const double gx = (grid.height(i + 1, j) - grid.height(i - 1, j)) / two_cells;
      const double gy = (grid.height(i, j + 1) - grid.height(i, j - 1)) / two_cells;
      const double angle = std::atan(std::hypot(gx, gy));
      // flank cells only: both neighbours across the slope hold material (not the toe)
      if (angle > min_angle_rad && grid.height(i + 1, j) > 0 && grid.height(i - 1, j) > 0 &&
          grid.height(i, j + 1) > 0 && grid.height(i, j - 1) > 0)
        angles.push_back(angle);
    }
  if (angles.empty()) return 0.0;
  std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
  return angles[angles.size() / 2];
}

HeapExtents heap_extents(const HeightGrid& grid, double foot_m) {
  const CellIndex peak = highest_cell(grid);
  auto reach = [&](int di, int dj) {
    int k = 0;
    for (;; ++k) {
      const int i = peak.i + (k + 1) * di, j = peak.j + (k + 1) * dj;
      if (i < 0 || j < 0 || i >= grid.cells_x() || j >= grid.cells_y() || grid.height(i, j) < foot_m) break;
    }
    return (k + 0.5) * grid.cell_size_m() * std::hypot(di, dj);
  };
  HeapExtents e;
  e.along_axes_m = (reach(1, 0) + reach(-1, 0) + reach(0, 1) + reach(0, -1)) / 4.0;
  e.along_diagonals_m = (reach(1, 1) + reach(-1, -1) + reach(1, -1) + reach(-1, 1)) / 4.0;
  return e;
}

}  // namespace harbour::bulk
