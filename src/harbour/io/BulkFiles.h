#pragma once

#include <string>
#include <vector>

#include "harbour/bulk/BulkScene.h"
#include "harbour/bulk/Grab.h"
#include "harbour/bulk/HeightGrid.h"
#include "harbour/bulk/Material.h"
#include "harbour/io/YamlFile.h"
#include "harbour/sim/Vessel.h"

namespace harbour::io {

/// Reads `materials:` from a materials file (see data/materials.yaml).
std::vector<bulk::Material> load_materials(const YamlFile& file);
std::vector<bulk::Material> load_materials(const std::string& path);

using ScenarioGrid = bulk::GridPlacement;
using ScenarioHeap = bulk::HeapPlacement;

/// A bulk-handling scenario (data/scenarios/*.yaml, section `bulk`): a scene and the demo's grab.
struct BulkScenario : bulk::BulkScene {
  bulk::GrabSettings grab;
};

/// Reads a `bulk:` section's material, spill level, grids and heaps (`at` names it in errors:
/// "bulk", "exercise.bulk"); `materials` resolves the material's name; a grid on a hold (`vessel_hold`) needs
/// the scene's bulk carrier.
bulk::BulkScene read_bulk_scene(const YamlFile& file, const YAML::Node& section, const std::string& at,
                                const std::vector<bulk::Material>& materials,
                                const sim::VesselGeometry* vessel = nullptr);

/// Reads a bulk scenario; `materials` resolves its material name.
BulkScenario load_bulk_scenario(const YamlFile& file, const std::vector<bulk::Material>& materials);
BulkScenario load_bulk_scenario(const std::string& path, const std::vector<bulk::Material>& materials);

}  // namespace harbour::io
