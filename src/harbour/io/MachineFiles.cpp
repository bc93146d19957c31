#include "harbour/io/MachineFiles.h"

#include <filesystem>

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
  const YAML::Node spreader = f.required(m, "spreader", "machine");
  s.spreader_mass_kg = f.number(spreader, "mass_kg", "machine.spreader", 0.0, kHuge, true);
  // the spreader's length lies along the quay (the crane's y), like the containers on the vessel
  const double length = f.number(spreader, "length_m", "machine.spreader", 0.0, 30.0, true);
  s.spreader_half_extents_m = {0.5 * f.number(spreader, "width_m", "machine.spreader", 0.0, 10.0, true),
                               0.5 * length,
                               0.5 * f.number(spreader, "height_m", "machine.spreader", 0.0, 10.0, true)};
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
