#pragma once

#include "harbour/bulk/HeightGrid.h"

namespace harbour::bulk {

/// The highest cell of a grid.
CellIndex highest_cell(const HeightGrid& grid);

/// Angle of repose of a single heap [rad]: least-squares slope of height against distance from the peak
/// over the flank (cells between 15% and 85% of the peak height), i.e. the cone that fits the heap.
double fitted_cone_angle(const HeightGrid& grid);

/// Median surface angle [rad] over cells whose central-difference slope exceeds `min_angle_rad`:
/// the flank angle of any heap shape (dug, several peaks).
double median_flank_angle(const HeightGrid& grid, double min_angle_rad);

/// Extents of a heap from its peak to where the height falls below `foot_m`, along axes and diagonals.
struct HeapExtents {
  double along_axes_m = 0;       ///< [m] mean of +x, -x, +y, -y
  double along_diagonals_m = 0;  ///< [m] mean of the four diagonals
  /// Isotropy: diagonal over axis extent; 1 for a round heap, 0.71 for the paper's 4-neighbour diamond.
  double ratio() const { return along_diagonals_m / along_axes_m; }
};
HeapExtents heap_extents(const HeightGrid& grid, double foot_m);

}  // namespace harbour::bulk
