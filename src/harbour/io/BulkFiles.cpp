#include "harbour/io/BulkFiles.h"

#include <algorithm>

#include "harbour/core/Units.h"

namespace harbour::io {
namespace {

// a bulk grid lies in the harbour: its origin and spill level within 2 km (docs/reliability.md); a grid at
// 1.8e308 m made the relaxation's arithmetic never settle
constexpr double kSite_m = 2000.0;

std::string item(const std::string& list, std::size_t n) {
  return list + "[" + std::to_string(n) + "]";
}

}  // namespace

std::vector<bulk::Material> load_materials(const YamlFile& file) {
  std::vector<bulk::Material> materials;
  const YAML::Node list = file.sequence(file.root(), "materials", "");
  for (std::size_t n = 0; n < list.size(); ++n) {
    const YAML::Node m = list[n];
    const std::string path = item("materials", n);
    bulk::Material material;
    material.name = file.text(m, "name", path);
    if (std::any_of(materials.begin(), materials.end(),
                    [&](const auto& o) { return o.name == material.name; }))
      file.fail(m["name"], path + ".name", "duplicate material '" + material.name + "'");
    material.bulk_density_kg_m3 = file.number(m, "bulk_density_kg_m3", path, 0.0, 25000.0, true);
    material.angle_of_repose_rad =
        core::deg_to_rad(file.number(m, "angle_of_repose_deg", path, 0.0, 90.0, true, true));
    material.flow_friction_rad =
        core::deg_to_rad(file.number(m, "flow_friction_deg", path, 0.0, 90.0, true, true));
    if (material.flow_friction_rad > material.angle_of_repose_rad)
      file.fail(m["flow_friction_deg"], path + ".flow_friction_deg",
                "flowing material cannot hold a steeper slope than the angle of repose");
    material.compression_gain = file.number_or(m, "compression_gain", path, 1.0, 0.0, 1000.0);
    materials.push_back(material);
  }
  if (materials.empty()) file.fail(list, "materials", "no material defined");
  file.check_unknown_keys();
  return materials;
}

std::vector<bulk::Material> load_materials(const std::string& path) {
  return load_materials(YamlFile::load(path));
}

namespace {

// a grid on a bulk carrier's hold floor: it moves with the vessel
void read_vessel_hold(const YamlFile& file, const YAML::Node& g, const std::string& path,
                      const sim::VesselGeometry* vessel, bulk::GridPlacement& grid) {
  for (const char* key : {"cells_x", "cells_y", "origin_x_m", "origin_y_m", "origin_z_m", "yaw_deg",
                          "roll_amplitude_deg", "roll_period_s"})
    if (file.optional(g, key, path))
      file.fail(g[key], path + "." + key, "a vessel hold's grid is its floor and moves with the vessel");
  const int number = file.integer(g, "vessel_hold", path, 1, 20);
  if (!vessel || vessel->placement().vessel.kind != sim::VesselKind::kBulk)
    file.fail(g["vessel_hold"], path + ".vessel_hold",
              "a vessel hold needs the exercise's vessel to be a bulk carrier");
  const sim::VesselSettings::Hold* hold = vessel->hold(number);
  if (!hold)
    file.fail(g["vessel_hold"], path + ".vessel_hold",
              "vessel " + vessel->placement().vessel.name + " has no hold " + std::to_string(number));
  const sim::VesselGeometry::Floor floor = vessel->hold_floor(*hold);
  const double cell = grid.settings.cell_size_m;
  grid.settings.cells_x = static_cast<int>(std::floor(floor.breadth_m / cell));
  grid.settings.cells_y = static_cast<int>(std::floor(floor.length_m / cell));
  if (grid.settings.cells_x < 1 || grid.settings.cells_y < 1 || grid.settings.cells_x > 8192 ||
      grid.settings.cells_y > 8192)
    file.fail(g["cell_size_m"], path + ".cell_size_m",
              "does not divide the hold floor into 1 to 8192 cells a side");
  // centred on the floor (vessel frame x across the beam is the grid's x, y along the vessel its y)
  grid.on_vessel = true;
  grid.origin_x_m = floor.corner_m.x + 0.5 * (floor.breadth_m - grid.settings.cells_x * cell);
  grid.origin_y_m = floor.corner_m.y + 0.5 * (floor.length_m - grid.settings.cells_y * cell);
  grid.origin_z_m = floor.corner_m.z;
}

}  // namespace

bulk::BulkScene read_bulk_scene(const YamlFile& file, const YAML::Node& section, const std::string& at,
                                const std::vector<bulk::Material>& materials,
                                const sim::VesselGeometry* vessel) {
  bulk::BulkScene scenario;
  const std::string material = file.text(section, "material", at);
  const auto found =
      std::find_if(materials.begin(), materials.end(), [&](const auto& m) { return m.name == material; });
  if (found == materials.end())
    file.fail(section["material"], at + ".material", "unknown material '" + material + "'");
  scenario.material = *found;
  scenario.spill_level_m = file.number_or(section, "spill_level_m", at, 0.0, -kSite_m, kSite_m);

  const YAML::Node grids = file.sequence(section, "grids", at);
  for (std::size_t n = 0; n < grids.size(); ++n) {
    const YAML::Node g = grids[n];
    const std::string path = item(at + ".grids", n);
    bulk::GridPlacement grid;
    grid.name = file.text(g, "name", path);
    for (std::size_t k = 0; k < n; ++k)
      if (scenario.grids[k].name == grid.name) file.fail(g["name"], path + ".name", "grid listed twice");
    grid.settings.cell_size_m = file.number(g, "cell_size_m", path, 0.0, 100.0, true);
    if (file.optional(g, "vessel_hold", path)) {
      read_vessel_hold(file, g, path, vessel, grid);
    } else {
      grid.settings.cells_x = file.integer(g, "cells_x", path, 1, 8192);
      grid.settings.cells_y = file.integer(g, "cells_y", path, 1, 8192);
      grid.origin_x_m = file.number_or(g, "origin_x_m", path, 0.0, -kSite_m, kSite_m);
      grid.origin_y_m = file.number_or(g, "origin_y_m", path, 0.0, -kSite_m, kSite_m);
      grid.origin_z_m = file.number_or(g, "origin_z_m", path, 0.0, -kSite_m, kSite_m);
      grid.yaw_rad = core::deg_to_rad(file.number_or(g, "yaw_deg", path, 0.0, -360.0, 360.0));
      grid.roll_amplitude_rad =
          core::deg_to_rad(file.number_or(g, "roll_amplitude_deg", path, 0.0, 0.0, 30.0));
      grid.roll_period_s = file.number_or(g, "roll_period_s", path, 0.0, 0.0, 600.0);
    }
    grid.outflow_m3_per_s = file.number_or(g, "outflow_m3_per_s", path, 0.0, 0.0, 100.0);
    grid.fill_m = file.number_or(g, "fill_m", path, 0.0, 0.0, 50.0);
    scenario.grids.push_back(grid);
  }
  if (scenario.grids.empty()) file.fail(grids, at + ".grids", "no grid defined");

  if (file.optional(section, "heaps", at)) {
    const YAML::Node heaps = file.sequence(section, "heaps", at);
    for (std::size_t n = 0; n < heaps.size(); ++n) {
      const YAML::Node h = heaps[n];
      const std::string path = item(at + ".heaps", n);
      bulk::HeapPlacement heap;
      const std::string grid = file.text(h, "grid", path);
      const auto g =
          std::find_if(scenario.grids.begin(), scenario.grids.end(), [&](auto& s) { return s.name == grid; });
      if (g == scenario.grids.end()) file.fail(h["grid"], path + ".grid", "unknown grid '" + grid + "'");
      heap.grid = static_cast<int>(g - scenario.grids.begin());
      heap.x_m = file.number(h, "x_m", path, 0.0, g->settings.cells_x * g->settings.cell_size_m);
      heap.y_m = file.number(h, "y_m", path, 0.0, g->settings.cells_y * g->settings.cell_size_m);
      heap.volume_m3 = file.number(h, "volume_m3", path, 0.0, 1e7);
      scenario.heaps.push_back(heap);
    }
  }

  return scenario;
}

BulkScenario load_bulk_scenario(const YamlFile& file, const std::vector<bulk::Material>& materials) {
  BulkScenario scenario;
  const YAML::Node section = file.required(file.root(), "bulk", "");
  static_cast<bulk::BulkScene&>(scenario) = read_bulk_scene(file, section, "bulk", materials);
  const YAML::Node grab = file.required(section, "grab", "bulk");
  bulk::GrabSettings& s = scenario.grab;
  s.width_m = file.number(grab, "width_m", "bulk.grab", 0.0, 50.0, true);
  s.max_opening_m = file.number(grab, "max_opening_m", "bulk.grab", 0.0, 50.0, true);
  s.max_depth_m = file.number(grab, "max_depth_m", "bulk.grab", 0.0, 20.0, true);
  s.sinking_speed_mps = file.number(grab, "sinking_speed_mps", "bulk.grab", 0.0, 20.0, true);
  s.spill_speed_mps = file.number(grab, "spill_speed_mps", "bulk.grab", 0.0, 50.0, true);
  s.capacity_m3 = file.number(grab, "capacity_m3", "bulk.grab", 0.0, 500.0, true);
  s.closing_time_s = file.number(grab, "closing_time_s", "bulk.grab", 0.0, 120.0, true);
  file.check_unknown_keys();
  return scenario;
}

BulkScenario load_bulk_scenario(const std::string& path, const std::vector<bulk::Material>& materials) {
  return load_bulk_scenario(YamlFile::load(path), materials);
}

}  // namespace harbour::io
