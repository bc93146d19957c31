#include "harbour/bulk/BulkPublish.h"

#include <algorithm>

namespace harbour::bulk {

int publish(const BulkWorld& world, scene::BulkView& view) {
  int copied = 0;
  view.grids.resize(static_cast<std::size_t>(world.grid_count()));
  for (int g = 0; g < world.grid_count(); ++g) {
    const HeightGrid& grid = world.grid(g);
    scene::BulkView::Grid& out = view.grids[static_cast<std::size_t>(g)];
    const bool fresh = out.cells_x != grid.cells_x() || out.cells_y != grid.cells_y();
    if (fresh) {
      out.cells_x = grid.cells_x();
      out.cells_y = grid.cells_y();
      out.cell_m = grid.cell_size_m();
      out.tile_cells = HeightGrid::kTileCells;
      out.tiles_x = grid.tiles_x();
      out.tiles_y = grid.tiles_y();
      out.heights.assign(static_cast<std::size_t>(out.cells_x * out.cells_y), 0.0f);
      out.tile_version.assign(static_cast<std::size_t>(out.tiles_x * out.tiles_y), 0);
    }
    out.pose = grid.pose();
    for (int tj = 0; tj < out.tiles_y; ++tj)
      for (int ti = 0; ti < out.tiles_x; ++ti) {
        const std::uint32_t version = grid.tile_version(ti, tj);
        std::uint32_t& seen = out.tile_version[static_cast<std::size_t>(tj * out.tiles_x + ti)];
        if (!fresh && seen == version) continue;
        seen = version;
        const int i_end = std::min((ti + 1) * out.tile_cells, out.cells_x);
        const int j_end = std::min((tj + 1) * out.tile_cells, out.cells_y);
        for (int j = tj * out.tile_cells; j < j_end; ++j)
          for (int i = ti * out.tile_cells; i < i_end; ++i)
            out.heights[static_cast<std::size_t>(j * out.cells_x + i)] =
                static_cast<float>(grid.height(i, j));
        ++copied;
      }
  }
  view.parcels.clear();
  for (const Parcel& p : world.parcels())
    view.parcels.push_back({p.position, p.volume_m3});
  return copied;
}

}  // namespace harbour::bulk
