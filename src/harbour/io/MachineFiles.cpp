#include "harbour/io/MachineFiles.h"

#include <filesystem>
#include <stdexcept>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/io/ReevingFiles.h"

namespace harbour::io {
namespace {

// physical ranges (docs/reliability.md): wide enough for any real quay crane, narrow enough that the
// multibody solver sees well-conditioned masses and forces
constexpr double kMaxForce_n = 1e8;  ///< [N] 10 000 t: above any crane drive or brake
constexpr double kRails_m = 2000.0;  ///< [m] a quay's rails and a trolley's girder lie within this

sim::DriveSettings read_drive(const YamlFile& f, const YAML::Node& parent, const std::string& at) {
  const YAML::Node d = f.required(parent, "drive", at);
  const std::string p = at + ".drive";
  sim::DriveSettings s;
  s.max_speed_mps = f.number(d, "max_speed_mps", p, 0.0, 100.0, true);
  s.acceleration_mps2 = f.number(d, "acceleration_mps2", p, 0.0, 100.0, true);
  s.deceleration_mps2 = f.number(d, "deceleration_mps2", p, 0.0, 100.0, true);
  s.emergency_deceleration_mps2 = f.number(d, "emergency_deceleration_mps2", p, 0.0, 100.0, true);
  s.max_force_n = f.number(d, "max_force_n", p, 0.0, kMaxForce_n, true);
  s.brake_force_n = f.number(d, "brake_force_n", p, 0.0, kMaxForce_n, true);
  s.min_position_m = f.number(d, "min_position_m", p, -kRails_m, kRails_m);
  s.max_position_m = f.number(d, "max_position_m", p, -kRails_m, kRails_m);
  if (s.max_position_m <= s.min_position_m)
    f.fail(d["max_position_m"], p + ".max_position_m", "must exceed min_position_m");
  return s;
}

sim::SpreaderSettings read_spreader(const YamlFile& f, const YAML::Node& m) {
  // the spreader's length lies along the quay (the crane's y), like the containers on the vessel
  const YAML::Node node = f.required_map(m, "spreader", "machine");
  const std::string at = "machine.spreader";
  sim::SpreaderSettings s;
  // spreader and headblock: 7-15 t on real cranes (twin-lift spreaders up to ~20 t)
  s.mass_kg = f.number(node, "mass_kg", at, 1000.0, 50000.0);
  s.width_m = f.number(node, "width_m", at, 0.5, 5.0);
  s.height_m = f.number(node, "height_m", at, 0.2, 5.0);
  const YAML::Node sizes = f.required_map(node, "settings", at);
  const char* names[] = {"20ft", "40ft", "45ft"};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string p = at + ".settings." + names[k];
    const YAML::Node size = f.required_map(sizes, names[k], at + ".settings");
    s.length_m[k] = f.number(size, "length_m", p, k == 0 ? 0.0 : s.length_m[k - 1], 30.0, true);
    s.pin_span_m[k] = f.number(size, "twistlock_span_m", p, 0.0, s.length_m[k], true);
  }
  s.pin_track_m = f.number(node, "twistlock_track_m", at, 0.0, s.width_m, true);
  const std::string initial = f.text(node, "initial_size", at);
  if (initial == "20ft") {
    s.initial_size = sim::SpreaderSize::k20ft;
  } else if (initial == "40ft") {
    s.initial_size = sim::SpreaderSize::k40ft;
  } else if (initial == "45ft") {
    s.initial_size = sim::SpreaderSize::k45ft;
  } else {
    f.fail(node["initial_size"], at + ".initial_size", "unknown size '" + initial + "' (20ft, 40ft, 45ft)");
  }
  s.telescope_speed_mps = f.number(node, "telescope_speed_mps", at, 0.0, 5.0, true);
  const YAML::Node flippers = f.required_map(node, "flippers", at);
  const std::string fp = at + ".flippers";
  s.flipper_time_s = f.number(flippers, "swing_time_s", fp, 0.0, 60.0, true);
  s.flipper_depth_m = f.number(flippers, "depth_m", fp, 0.0, 2.0, true);
  s.flipper_flare_rad = core::deg_to_rad(f.number(flippers, "flare_deg", fp, 0.0, 60.0));
  s.flipper_gap_m = f.number(flippers, "gap_m", fp, 0.0, 0.2);
  s.flipper_arm_m = f.number(flippers, "arm_m", fp, 0.0, s.width_m / 2, true);
  return s;
}

sim::BoomSettings read_boom(const YamlFile& f, const YAML::Node& m) {
  const YAML::Node node = f.required_map(m, "boom", "machine");
  const std::string at = "machine.boom";
  sim::BoomSettings s;
  const double top = core::deg_to_rad(f.number(node, "max_angle_deg", at, 0.0, 90.0, true));
  const double speed = top / f.number(node, "luffing_time_s", at, 0.0, 3600.0, true);
  const double ramp_s = f.number(node, "ramp_time_s", at, 0.0, 60.0, true);
  s.drive = {speed, speed / ramp_s, speed / ramp_s, 4 * speed / ramp_s, 1.0, 1.0, 0.0, top};
  s.trolley_park_x_m = f.number(node, "trolley_park_x_m", at, -kRails_m, kRails_m);
  return s;
}

// the structure StsCrane relies on: one hoist drum (the crane commands one), and every rope passing a
// sheave on the headblock (its falls carry the load)
void check_sts_hoist(const YamlFile& f, const YAML::Node& at, const cable::ReevingSettings& r) {
  constexpr int kHeadblock = 2;  // reeving body index, as checked above
  int drums = 0;
  for (const cable::ElementSettings& e : r.elements)
    drums += e.kind == cable::ElementKind::kDrum ? 1 : 0;
  if (drums != 1)
    f.fail(at, "machine.hoist_reeving",
           "the STS hoist has one drum; the reeving has " + std::to_string(drums));
  for (const cable::RopeSettings& rope : r.ropes) {
    bool on_headblock = false;
    for (const int e : rope.path)
      on_headblock |= r.elements[static_cast<std::size_t>(e)].kind == cable::ElementKind::kSheave &&
                      r.elements[static_cast<std::size_t>(e)].mount.body == kHeadblock;
    if (!on_headblock)
      f.fail(at, "machine.hoist_reeving",
             "rope '" + rope.name + "' passes no sheave on the headblock, so it cannot carry the spreader");
  }
}

sim::StsCraneSettings read_sts_crane(const YamlFile& f, const std::string& folder) {
  sim::StsCraneSettings s;
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  if (const std::string kind = f.text(m, "kind", "machine"); kind != "sts")
    f.fail(m["kind"], "machine.kind", "this is an STS file (kind: sts), not a '" + kind + "'");
  f.text(m, "name", "machine");  // the machine's label
  const YAML::Node gantry = f.required_map(m, "gantry", "machine");
  // a quay crane's structure: 600-2000 t; its trolley (with cab and machinery) 20-150 t
  s.gantry_mass_kg = f.number(gantry, "mass_kg", "machine.gantry", 1e5, 1e7);
  s.gantry_drive = read_drive(f, gantry, "machine.gantry");
  const YAML::Node trolley = f.required_map(m, "trolley", "machine");
  s.trolley_mass_kg = f.number(trolley, "mass_kg", "machine.trolley", 5000.0, 5e5);
  s.trolley_rail_height_m = f.number(trolley, "rail_height_m", "machine.trolley", 10.0, 100.0);
  s.trolley_drive = read_drive(f, trolley, "machine.trolley");
  const YAML::Node hoist_limits = f.required_map(m, "hoist", "machine");
  s.hoist_upper_limit_m =
      f.number(hoist_limits, "upper_limit_m", "machine.hoist", -100.0, s.trolley_rail_height_m - 2.0);
  s.hoist_lower_limit_m =
      f.number(hoist_limits, "lower_limit_m", "machine.hoist", -100.0, s.hoist_upper_limit_m, false, true);
  s.spreader = read_spreader(f, m);
  s.boom = read_boom(f, m);
  if (s.boom.trolley_park_x_m < s.trolley_drive.min_position_m)
    f.fail(m["boom"]["trolley_park_x_m"], "machine.boom.trolley_park_x_m",
           "is landside of the trolley's travel (machine.trolley.drive.min_position_m)");
  const YAML::Node t = f.required_map(m, "twistlocks", "machine");
  s.twistlocks.lateral_tolerance_m = f.number(t, "lateral_tolerance_m", "machine.twistlocks", 0.0, 1.0, true);
  s.twistlocks.landed_gap_m = f.number(t, "landed_gap_m", "machine.twistlocks", 0.0, 1.0, true);

  const std::string reeving = f.text(m, "hoist_reeving", "machine");
  const std::string reeving_path = (std::filesystem::path(folder) / reeving).lexically_normal().string();
  if (!std::filesystem::is_regular_file(reeving_path))
    f.fail(m["hoist_reeving"], "machine.hoist_reeving", "no such file: " + reeving_path);
  const ReevingFile hoist = load_reeving(reeving_path);
  if (hoist.bodies != std::vector<std::string>{"gantry", "trolley", "headblock"})
    f.fail(m["hoist_reeving"], "machine.hoist_reeving",
           "the hoist reeving's bodies must be [gantry, trolley, headblock]");
  check_sts_hoist(f, m["hoist_reeving"], hoist.reeving);
  s.hoist = hoist.reeving;
  s.controls = read_control_table(f, m, "machine");
  try {
    const sim::StsControlSlots slots(s.controls);  // every control the STS reads, of its kind
  } catch (const std::invalid_argument& e) {
    f.fail(m["controls"], "machine.controls", e.what());
  }
  const YAML::Node cab = f.required_map(m, "cab", "machine");
  s.cab_position_m = f.vector3(f.required(cab, "position_m", "machine.cab"), "machine.cab.position_m", 100.0);
  s.eye_m = f.vector3(f.required(cab, "eye_m", "machine.cab"), "machine.cab.eye_m", 5.0);
  return s;
}

}  // namespace

sim::StsCraneSettings load_sts_crane(const YamlFile& f, const std::string& folder) {
  sim::StsCraneSettings s = read_sts_crane(f, folder);
  f.check_unknown_keys();
  return s;
}

sim::StsCraneSettings load_sts_crane(const std::string& path) {
  return load_sts_crane(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

std::string machine_file_kind(const std::string& path) {
  const YamlFile f = YamlFile::load(path);
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  const std::string kind = f.text(m, "kind", "machine");
  if (kind != "sts") f.fail(m["kind"], "machine.kind", "a machine is one of: sts (not '" + kind + "')");
  return kind;
}

}  // namespace harbour::io
