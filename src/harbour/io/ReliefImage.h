#pragma once

#include <span>
#include <string>

#include "harbour/bulk/HeightGrid.h"

namespace harbour::io {

/// Writes a shaded-relief PNG of `grids` side by side (hill shading lit from the north-west, colour by
/// height, bare floor grey); grids larger than `max_side_px` are subsampled. Throws std::runtime_error.
void write_relief_png(const std::string& path, std::span<const bulk::HeightGrid* const> grids,
                      int max_side_px = 512);

}  // namespace harbour::io
