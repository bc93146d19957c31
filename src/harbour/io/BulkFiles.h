#pragma once

#include <string>
#include <vector>

#include "harbour/bulk/Grab.h"
#include "harbour/bulk/HeightGrid.h"
#include "harbour/bulk/Material.h"
#include "harbour/io/YamlFile.h"

namespace harbour::io {

/// Reads `materials:` from a materials file (see data/materials.yaml).
std::vector<bulk::Material> load_materials(const YamlFile& file);
std::vector<bulk::Material> load_materials(const std::string& path);

/// A grid of a bulk scenario with its placement and optional rolling motion.
struct ScenarioGrid {
  std::string name;
  bulk::GridSettings settings;
  double origin_x_m = 0, origin_y_m = 0, origin_z_m = 0;  ///< [m] world position of the grid corner
  double yaw_rad = 0;                                     ///< [rad] about world z
  double roll_amplitude_rad = 0;                          ///< [rad] rolling about the grid's centre line
  double roll_period_s = 0;                               ///< [s] 0: no motion
};

/// An initial heap: a cone at the angle of repose.
struct ScenarioHeap {
  int grid = 0;
  double x_m = 0, y_m = 0;  ///< [m] centre, grid frame
  double volume_m3 = 0;
};

/// A bulk-handling scenario (data/scenarios/*.yaml, section `bulk`).
struct BulkScenario {
  bulk::Material material;
  double spill_level_m = 0;
  std::vector<ScenarioGrid> grids;
  std::vector<ScenarioHeap> heaps;
  bulk::GrabSettings grab;
};

/// Reads a bulk scenario; `materials` resolves its material name.
BulkScenario load_bulk_scenario(const YamlFile& file, const std::vector<bulk::Material>& materials);
BulkScenario load_bulk_scenario(const std::string& path, const std::vector<bulk::Material>& materials);

}  // namespace harbour::io
