#include "harbour/io/MachineFiles.h"

#include <filesystem>
#include <stdexcept>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/io/MachineFileType.h"
#include "harbour/io/MotionFiles.h"
#include "harbour/io/ReevingFiles.h"

namespace harbour::io {
// the cab: where it rides, the design eye in it, and the design view (the line of sight from the cab's x
// axis, and the vertical field of view a desktop picture shows: a human's binocular field spans about 120
// degrees vertically, a floor window or a windscreen less)
CabFields read_cab(const YamlFile& f, const YAML::Node& machine, double reach_m) {
  const YAML::Node cab = f.required_map(machine, "cab", "machine");
  CabFields c;
  c.position_m = f.vector3(f.required(cab, "position_m", "machine.cab"), "machine.cab.position_m", reach_m);
  c.eye_m = f.vector3(f.required(cab, "eye_m", "machine.cab"), "machine.cab.eye_m", 5.0);
  c.sight.yaw_rad = core::deg_to_rad(f.number_or(cab, "sight_yaw_deg", "machine.cab", 0.0, -180.0, 180.0));
  c.sight.pitch_rad = core::deg_to_rad(f.number(cab, "sight_pitch_deg", "machine.cab", -90.0, 30.0));
  c.sight.fov_vertical_rad =
      core::deg_to_rad(f.number_or(cab, "fov_vertical_deg", "machine.cab", 43.0, 20.0, 110.0));
  if (f.optional(cab, "look_limits_deg", "machine.cab")) {
    const YAML::Node limits = f.required(cab, "look_limits_deg", "machine.cab");
    if (!limits.IsSequence() || limits.size() != 2)
      f.fail(limits, "machine.cab.look_limits_deg", "expected [left-right, up-down] in degrees");
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string at = "machine.cab.look_limits_deg[" + std::to_string(k) + "]";
      const double deg = f.number_at(limits[k], at);
      if (!(deg >= 0.0 && deg <= 180.0)) f.fail(limits[k], at, "0-180 degrees");
      (k == 0 ? c.sight.look_yaw_rad : c.sight.look_pitch_rad) = core::deg_to_rad(deg);
    }
  }
  return c;
}

// every control the machine reads is in its table, of its kind; a missing or mistyped one names the list
void require_controls(const YamlFile& f, const YAML::Node& machine, const scene::ControlTable& table,
                      std::initializer_list<std::pair<const char*, scene::ControlKind>> needed) {
  for (const auto& [label, kind] : needed) {
    try {
      table.slot(label, kind);
    } catch (const std::invalid_argument& e) {
      f.fail(machine["controls"], "machine.controls", e.what());
    }
  }
}

cable::ReevingSettings read_reeving_file(const YamlFile& f, const YAML::Node& map, const std::string& key,
                                         const std::string& at, const std::string& folder,
                                         const std::vector<std::string>& bodies, int drums) {
  const std::string file = f.text(map, key, at);
  const std::string path = (std::filesystem::path(folder) / file).lexically_normal().string();
  if (!std::filesystem::is_regular_file(path)) f.fail(map[key], at + "." + key, "no such file: " + path);
  const ReevingFile reeving = load_reeving(path);
  if (reeving.bodies != bodies) {
    std::string list;
    for (const std::string& b : bodies)
      list += (list.empty() ? "" : ", ") + b;
    f.fail(map[key], at + "." + key, "the reeving's bodies must be [" + list + "]");
  }
  int found = 0;
  for (const cable::ElementSettings& e : reeving.reeving.elements)
    found += e.kind == cable::ElementKind::kDrum ? 1 : 0;
  if (found != drums)
    f.fail(map[key], at + "." + key,
           "needs " + std::to_string(drums) + " drum(s); the reeving has " + std::to_string(found));
  return reeving.reeving;
}

// A wheeled machine's chassis body (machine.chassis): its mass and its box about its centre of mass.
std::pair<double, core::Vec3> read_chassis_box(const YamlFile& f, const YAML::Node& m, double min_kg,
                                               double max_kg) {
  const YAML::Node c = f.required_map(m, "chassis", "machine");
  const double mass_kg = f.number(c, "mass_kg", "machine.chassis", min_kg, max_kg);
  const core::Vec3 half =
      f.vector3(f.required(c, "half_extents_m", "machine.chassis"), "machine.chassis.half_extents_m", 10.0);
  if (!(half.x >= 0.2 && half.y >= 0.2 && half.z >= 0.1))
    f.fail(c["half_extents_m"], "machine.chassis.half_extents_m", "must be at least [0.2, 0.2, 0.1] m");
  return {mass_kg, half};
}

// A vehicle's driving controls: steering wheel, pedals, the direction selector (reverse, neutral, forward),
// the parking brake (released, set), emergency stop and horn.
void require_driving_controls(const YamlFile& f, const YAML::Node& m, const scene::ControlTable& controls) {
  using K = scene::ControlKind;
  require_controls(f, m, controls,
                   {{"steer", K::kAxis},
                    {"throttle", K::kAxis},
                    {"brake", K::kAxis},
                    {"direction", K::kSwitch},
                    {"parking_brake", K::kSwitch},
                    {"emergency_stop", K::kButton},
                    {"horn", K::kButton}});
  if (controls[controls.find("direction")].positions !=
      std::vector<std::string>{"reverse", "neutral", "forward"})
    f.fail(m["controls"], "machine.controls",
           "'direction' must have the positions [reverse, neutral, forward]");
  if (controls[controls.find("parking_brake")].positions != std::vector<std::string>{"released", "set"})
    f.fail(m["controls"], "machine.controls", "'parking_brake' must have the positions [released, set]");
}

void check_machine_file_sections(const YamlFile& f) {
  check_motion_cues(f);
  f.read_elsewhere(f.root(), "looks", "");
  f.read_elsewhere(f.root(), "sounds", "");
}

namespace {
// `machine.kind`, one of the registered machine types (each machine folder's files)
std::string registered_kind(const YamlFile& f) {
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  const std::string kind = f.text(m, "kind", "machine");
  if (!find_machine_file_type(kind)) {
    std::string kinds;
    for (const MachineFileType* type : machine_file_types())
      kinds += std::string(kinds.empty() ? "" : ", ") + type->kind;
    f.fail(m["kind"], "machine.kind", "a machine is one of: " + kinds + " (not '" + kind + "')");
  }
  return kind;
}
}  // namespace

std::string machine_file_kind(const std::string& path) {
  return registered_kind(YamlFile::load(path));
}

scene::ControlTable machine_file_controls(const std::string& path) {
  const YamlFile f = YamlFile::load(path);
  registered_kind(f);
  return read_control_table(f, f.required_map(f.root(), "machine", ""), "machine");
}

}  // namespace harbour::io
