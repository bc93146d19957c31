#include "harbour/io/MachineFiles.h"

#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ReevingFiles.h"

namespace harbour::io {
namespace {

constexpr double kHuge = 1e12;

sim::DriveSettings read_drive(const YamlFile& f, const YAML::Node& parent, const std::string& at) {
  const YAML::Node d = f.required(parent, "drive", at);
  const std::string p = at + ".drive";
  sim::DriveSettings s;
  s.max_speed_mps = f.number(d, "max_speed_mps", p, 0.0, 100.0, true);
  s.acceleration_mps2 = f.number(d, "acceleration_mps2", p, 0.0, 100.0, true);
  s.deceleration_mps2 = f.number(d, "deceleration_mps2", p, 0.0, 100.0, true);
  s.emergency_deceleration_mps2 = f.number(d, "emergency_deceleration_mps2", p, 0.0, 100.0, true);
  s.max_force_n = f.number(d, "max_force_n", p, 0.0, kHuge, true);
  s.brake_force_n = f.number(d, "brake_force_n", p, 0.0, kHuge, true);
  s.min_position_m = f.number(d, "min_position_m", p, -1e6, 1e6);
  s.max_position_m = f.number(d, "max_position_m", p, -1e6, 1e6);
  if (s.max_position_m <= s.min_position_m)
    f.fail(d["max_position_m"], p + ".max_position_m", "must exceed min_position_m");
  return s;
}

sim::SpreaderSettings read_spreader(const YamlFile& f, const YAML::Node& m) {
  // the spreader's length lies along the quay (the crane's y), like the containers on the vessel
  const YAML::Node node = f.required(m, "spreader", "machine");
  const std::string at = "machine.spreader";
  sim::SpreaderSettings s;
  s.mass_kg = f.number(node, "mass_kg", at, 0.0, kHuge, true);
  s.width_m = f.number(node, "width_m", at, 0.0, 10.0, true);
  s.height_m = f.number(node, "height_m", at, 0.0, 10.0, true);
  const YAML::Node sizes = f.required(node, "settings", at);
  const char* names[] = {"20ft", "40ft", "45ft"};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string p = at + ".settings." + names[k];
    const YAML::Node size = f.required(sizes, names[k], at + ".settings");
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
  const YAML::Node flippers = f.required(node, "flippers", at);
  const std::string fp = at + ".flippers";
  s.flipper_time_s = f.number(flippers, "swing_time_s", fp, 0.0, 60.0, true);
  s.flipper_depth_m = f.number(flippers, "depth_m", fp, 0.0, 2.0, true);
  s.flipper_flare_rad = core::deg_to_rad(f.number(flippers, "flare_deg", fp, 0.0, 60.0));
  s.flipper_gap_m = f.number(flippers, "gap_m", fp, 0.0, 0.2);
  s.flipper_arm_m = f.number(flippers, "arm_m", fp, 0.0, s.width_m / 2, true);
  return s;
}

sim::BoomSettings read_boom(const YamlFile& f, const YAML::Node& m) {
  const YAML::Node node = f.required(m, "boom", "machine");
  const std::string at = "machine.boom";
  sim::BoomSettings s;
  const double top = core::deg_to_rad(f.number(node, "max_angle_deg", at, 0.0, 90.0, true));
  const double speed = top / f.number(node, "luffing_time_s", at, 0.0, 3600.0, true);
  const double ramp_s = f.number(node, "ramp_time_s", at, 0.0, 60.0, true);
  s.drive = {speed, speed / ramp_s, speed / ramp_s, 4 * speed / ramp_s, 1.0, 1.0, 0.0, top};
  s.trolley_park_x_m = f.number(node, "trolley_park_x_m", at, -1e3, 1e3);
  return s;
}

}  // namespace

sim::StsCraneSettings load_sts_crane(const YamlFile& f, const std::string& folder) {
  sim::StsCraneSettings s;
  const YAML::Node m = f.required(f.root(), "machine", "");
  const YAML::Node gantry = f.required(m, "gantry", "machine");
  s.gantry_mass_kg = f.number(gantry, "mass_kg", "machine.gantry", 0.0, kHuge, true);
  s.gantry_drive = read_drive(f, gantry, "machine.gantry");
  const YAML::Node trolley = f.required(m, "trolley", "machine");
  s.trolley_mass_kg = f.number(trolley, "mass_kg", "machine.trolley", 0.0, kHuge, true);
  s.trolley_rail_height_m = f.number(trolley, "rail_height_m", "machine.trolley", 0.0, 200.0, true);
  s.trolley_drive = read_drive(f, trolley, "machine.trolley");
  const YAML::Node hoist_limits = f.required(m, "hoist", "machine");
  s.hoist_upper_limit_m =
      f.number(hoist_limits, "upper_limit_m", "machine.hoist", -100.0, s.trolley_rail_height_m - 2.0);
  s.hoist_lower_limit_m =
      f.number(hoist_limits, "lower_limit_m", "machine.hoist", -100.0, s.hoist_upper_limit_m, false, true);
  s.spreader = read_spreader(f, m);
  s.boom = read_boom(f, m);
  if (s.boom.trolley_park_x_m < s.trolley_drive.min_position_m)
    f.fail(m["boom"]["trolley_park_x_m"], "machine.boom.trolley_park_x_m",
           "is landside of the trolley's travel (machine.trolley.drive.min_position_m)");
  const YAML::Node t = f.required(m, "twistlocks", "machine");
  s.twistlocks.lateral_tolerance_m = f.number(t, "lateral_tolerance_m", "machine.twistlocks", 0.0, 1.0, true);
  s.twistlocks.landed_gap_m = f.number(t, "landed_gap_m", "machine.twistlocks", 0.0, 1.0, true);

  const std::string reeving = f.text(m, "hoist_reeving", "machine");
  const std::string reeving_path = (std::filesystem::path(folder) / reeving).lexically_normal().string();
  if (!std::filesystem::exists(reeving_path))
    f.fail(m["hoist_reeving"], "machine.hoist_reeving", "no such file: " + reeving_path);
  const ReevingFile hoist = load_reeving(reeving_path);
  if (hoist.bodies != std::vector<std::string>{"gantry", "trolley", "headblock"})
    f.fail(m["hoist_reeving"], "machine.hoist_reeving",
           "the hoist reeving's bodies must be [gantry, trolley, headblock]");
  s.hoist = hoist.reeving;
  return s;
}

sim::StsCraneSettings load_sts_crane(const std::string& path) {
  return load_sts_crane(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

}  // namespace harbour::io
