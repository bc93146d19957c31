#pragma once

#include <cstdint>
#include <vector>

#include "harbour/core/Vec3.h"

namespace harbour::scene {

/// Bulk material as published for readers (the image generator): each grid's heights by tile, with a version
/// per tile so that a reader copies and re-meshes only the tiles that changed; the material in flight as
/// points. Plain data (core headers only). Sized once per grid; publishing then allocates nothing.
struct BulkView {
  struct Grid {
    core::Pose
        pose;  ///< grid frame in the world: origin at the outer corner of cell (0, 0), z up from its floor
    double cell_m = 0.1;
    int cells_x = 0, cells_y = 0;
    int tile_cells = 32;  ///< cells per tile side
    int tiles_x = 0, tiles_y = 0;
    std::vector<std::uint32_t> tile_version;  ///< tiles_x * tiles_y, row by row
    std::vector<float> heights;               ///< [m] cells_x * cells_y, row by row (j * cells_x + i)
  };
  std::vector<Grid> grids;
  struct Parcel {
    core::Vec3 position_m;
    double volume_m3 = 0.0;
  };
  std::vector<Parcel> parcels;
};

}  // namespace harbour::scene
