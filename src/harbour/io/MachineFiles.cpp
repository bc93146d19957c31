#include "harbour/io/MachineFiles.h"

#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/io/ReevingFiles.h"

namespace harbour::io {
namespace {

// physical ranges (docs/reliability.md): wide enough for any real quay crane, narrow enough that the
// multibody solver sees well-conditioned masses and forces
constexpr double kMaxForce_n = 1e8;  ///< [N] 10 000 t: above any crane drive or brake
constexpr double kRails_m = 2000.0;  ///< [m] a quay's rails and a trolley's girder lie within this

// `turns`: a rotary axis without end switches (slewing): no positions read
sim::DriveSettings read_drive(const YamlFile& f, const YAML::Node& parent, const std::string& at,
                              bool turns = false) {
  const YAML::Node d = f.required(parent, "drive", at);
  const std::string p = at + ".drive";
  sim::DriveSettings s;
  s.max_speed_mps = f.number(d, "max_speed_mps", p, 0.0, 100.0, true);
  s.acceleration_mps2 = f.number(d, "acceleration_mps2", p, 0.0, 100.0, true);
  s.deceleration_mps2 = f.number(d, "deceleration_mps2", p, 0.0, 100.0, true);
  s.emergency_deceleration_mps2 = f.number(d, "emergency_deceleration_mps2", p, 0.0, 100.0, true);
  s.max_force_n = f.number(d, "max_force_n", p, 0.0, kMaxForce_n, true);
  s.brake_force_n = f.number(d, "brake_force_n", p, 0.0, kMaxForce_n, true);
  if (turns) return s;
  s.min_position_m = f.number(d, "min_position_m", p, -kRails_m, kRails_m);
  s.max_position_m = f.number(d, "max_position_m", p, -kRails_m, kRails_m);
  if (s.max_position_m <= s.min_position_m)
    f.fail(d["max_position_m"], p + ".max_position_m", "must exceed min_position_m");
  return s;
}

// A drive moves what it carries: its force must give that mass [kg] the drive's acceleration, or the machine
// would never get going (a force of 1e-300 N reads as a drive, and nothing moves).
void check_drive_moves(const YamlFile& f, const YAML::Node& parent, const std::string& at,
                       const sim::DriveSettings& drive, double moved_kg, const char* what) {
  const double needed_n = moved_kg * drive.acceleration_mps2;
  const auto figure = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return std::string(text);
  };
  if (drive.max_force_n < needed_n)
    f.fail(f.required(parent, "drive", at)["max_force_n"], at + ".drive.max_force_n",
           figure(drive.max_force_n) + " N cannot give " + what + " (" + figure(moved_kg) +
               " kg) its acceleration of " + figure(drive.acceleration_mps2) + " m/s^2: it needs at least " +
               figure(needed_n) + " N");
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
  if (!f.optional(node, "flippers", at)) return s;  // none: they never come down
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

// the structure a spreader hoist relies on: one drum (the cab commands one), and every rope passing a sheave
// on the headblock, the reeving's last body (its falls carry the load)
void check_spreader_hoist(const YamlFile& f, const YAML::Node& at, const cable::ReevingSettings& r,
                          int headblock) {
  int drums = 0;
  for (const cable::ElementSettings& e : r.elements)
    drums += e.kind == cable::ElementKind::kDrum ? 1 : 0;
  if (drums != 1)
    f.fail(at, "machine.hoist_reeving", "the hoist has one drum; the reeving has " + std::to_string(drums));
  for (const cable::RopeSettings& rope : r.ropes) {
    bool on_headblock = false;
    for (const int e : rope.path)
      on_headblock |= r.elements[static_cast<std::size_t>(e)].kind == cable::ElementKind::kSheave &&
                      r.elements[static_cast<std::size_t>(e)].mount.body == headblock;
    if (!on_headblock)
      f.fail(at, "machine.hoist_reeving",
             "rope '" + rope.name + "' passes no sheave on the headblock, so it cannot carry the spreader");
  }
}

// a container spreader on its hoist ropes under a trolley whose centre runs `rail_height_m` up: the limit
// switches (machine.hoist), the spreader, its twistlocks and the reeving (over `bodies`, the headblock last)
sim::SpreaderHoistSettings read_spreader_hoist(const YamlFile& f, const YAML::Node& m,
                                               const std::string& folder,
                                               const std::vector<std::string>& bodies, double rail_height_m) {
  sim::SpreaderHoistSettings s;
  const YAML::Node hoist_limits = f.required_map(m, "hoist", "machine");
  s.upper_limit_m = f.number(hoist_limits, "upper_limit_m", "machine.hoist", -100.0, rail_height_m - 2.0);
  s.lower_limit_m =
      f.number(hoist_limits, "lower_limit_m", "machine.hoist", -100.0, s.upper_limit_m, false, true);
  s.spreader = read_spreader(f, m);
  const YAML::Node t = f.required_map(m, "twistlocks", "machine");
  s.twistlocks.lateral_tolerance_m = f.number(t, "lateral_tolerance_m", "machine.twistlocks", 0.0, 1.0, true);
  s.twistlocks.landed_gap_m = f.number(t, "landed_gap_m", "machine.twistlocks", 0.0, 1.0, true);
  const std::string reeving = f.text(m, "hoist_reeving", "machine");
  const std::string reeving_path = (std::filesystem::path(folder) / reeving).lexically_normal().string();
  if (!std::filesystem::is_regular_file(reeving_path))
    f.fail(m["hoist_reeving"], "machine.hoist_reeving", "no such file: " + reeving_path);
  const ReevingFile file = load_reeving(reeving_path);
  if (file.bodies != bodies) {
    std::string list;
    for (const std::string& b : bodies)
      list += (list.empty() ? "" : ", ") + b;
    f.fail(m["hoist_reeving"], "machine.hoist_reeving", "the hoist reeving's bodies must be [" + list + "]");
  }
  check_spreader_hoist(f, m["hoist_reeving"], file.reeving, static_cast<int>(bodies.size()) - 1);
  s.hoist = file.reeving;
  return s;
}

// the operator's cab: where it sits (within `reach_m` of the frame it is given in), the eye in it and the
// design line of sight
struct CabFields {
  core::Vec3 position_m, eye_m;
  sim::CabSight sight;
};
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
void require_controls(const YamlFile& f, const YAML::Node& machine, const sim::ControlTable& table,
                      std::initializer_list<std::pair<const char*, sim::ControlKind>> needed) {
  for (const auto& [label, kind] : needed) {
    try {
      table.slot(label, kind);
    } catch (const std::invalid_argument& e) {
      f.fail(machine["controls"], "machine.controls", e.what());
    }
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
  check_drive_moves(f, gantry, "machine.gantry", s.gantry_drive, s.gantry_mass_kg, "the crane");
  const YAML::Node trolley = f.required_map(m, "trolley", "machine");
  s.trolley_mass_kg = f.number(trolley, "mass_kg", "machine.trolley", 5000.0, 5e5);
  s.trolley_rail_height_m = f.number(trolley, "rail_height_m", "machine.trolley", 10.0, 100.0);
  s.trolley_drive = read_drive(f, trolley, "machine.trolley");
  check_drive_moves(f, trolley, "machine.trolley", s.trolley_drive, s.trolley_mass_kg, "the trolley");
  const sim::SpreaderHoistSettings rig =
      read_spreader_hoist(f, m, folder, {"gantry", "trolley", "headblock"}, s.trolley_rail_height_m);
  s.hoist_upper_limit_m = rig.upper_limit_m;
  s.hoist_lower_limit_m = rig.lower_limit_m;
  s.spreader = rig.spreader;
  s.twistlocks = rig.twistlocks;
  s.hoist = rig.hoist;
  s.boom = read_boom(f, m);
  if (s.boom.trolley_park_x_m < s.trolley_drive.min_position_m)
    f.fail(m["boom"]["trolley_park_x_m"], "machine.boom.trolley_park_x_m",
           "is landside of the trolley's travel (machine.trolley.drive.min_position_m)");
  s.controls = read_control_table(f, m, "machine");
  try {
    const sim::StsControlSlots slots(s.controls);  // every control the STS reads, of its kind
  } catch (const std::invalid_argument& e) {
    f.fail(m["controls"], "machine.controls", e.what());
  }
  const CabFields cab = read_cab(f, m, 100.0);
  s.cab_position_m = cab.position_m;
  s.eye_m = cab.eye_m;
  s.sight = cab.sight;
  return s;
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

// every rope of the reeving passes a mount on `body` (reeving body index)
void check_ropes_pass(const YamlFile& f, const YAML::Node& at, const std::string& field,
                      const cable::ReevingSettings& r, int body, const std::string& what) {
  for (const cable::RopeSettings& rope : r.ropes) {
    bool passes = false;
    for (const int e : rope.path)
      passes |= r.elements[static_cast<std::size_t>(e)].mount.body == body;
    if (!passes) f.fail(at, field, "rope '" + rope.name + "' " + what);
  }
}

// a load-moment limiter's capacity chart: [radius m, capacity t] points, radii increasing
std::vector<sim::CapacityPoint> read_capacity_chart(const YamlFile& f, const YAML::Node& map,
                                                    const std::string& at) {
  const YAML::Node chart = f.sequence(map, "chart", at, 100);
  if (chart.size() < 2)
    f.fail(map["chart"], at + ".chart", "needs at least two [radius m, capacity t] points");
  std::vector<sim::CapacityPoint> points;
  for (std::size_t n = 0; n < chart.size(); ++n) {
    const std::string p = at + ".chart[" + std::to_string(n) + "]";
    if (!chart[n].IsSequence() || chart[n].size() != 2) f.fail(chart[n], p, "is [radius m, capacity t]");
    const sim::CapacityPoint point{f.number_at(chart[n][0], p + "[0]"), f.number_at(chart[n][1], p + "[1]")};
    if (!(point.radius_m > 0.0 && point.radius_m < 200.0 && point.capacity_t > 0.0 &&
          point.capacity_t < 1000.0))
      f.fail(chart[n], p, "radius 0-200 m, capacity 0-1000 t");
    if (!points.empty() && point.radius_m <= points.back().radius_m)
      f.fail(chart[n], p, "radii must increase down the chart");
    points.push_back(point);
  }
  return points;
}

sim::MhcSettings read_mhc(const YamlFile& f, const std::string& folder) {
  sim::MhcSettings s;
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  if (const std::string kind = f.text(m, "kind", "machine"); kind != "mhc")
    f.fail(m["kind"], "machine.kind", "this is an MHC file (kind: mhc), not a '" + kind + "'");
  f.text(m, "name", "machine");

  const YAML::Node u = f.required_map(m, "undercarriage", "machine");
  s.undercarriage_mass_kg = f.number(u, "mass_kg", "machine.undercarriage", 1e4, 5e6);
  s.pad_half_spread_x_m = f.number(u, "pad_half_spread_x_m", "machine.undercarriage", 1.0, 50.0);
  s.pad_half_spread_y_m = f.number(u, "pad_half_spread_y_m", "machine.undercarriage", 1.0, 50.0);

  const YAML::Node h = f.required_map(m, "house", "machine");
  s.house_mass_kg = f.number(h, "mass_kg", "machine.house", 1e4, 5e6);
  s.house_com_m = f.vector3(f.required(h, "com_m", "machine.house"), "machine.house.com_m", 50.0);
  s.house_half_extents_m =
      f.vector3(f.required(h, "half_extents_m", "machine.house"), "machine.house.half_extents_m", 50.0);
  if (!(s.house_half_extents_m.x > 0.1 && s.house_half_extents_m.y > 0.1 && s.house_half_extents_m.z > 0.1))
    f.fail(h["half_extents_m"], "machine.house.half_extents_m", "must be over 0.1 m each");
  s.slew_drive = read_drive(f, f.required_map(h, "slew", "machine.house"), "machine.house.slew", true);

  const YAML::Node b = f.required_map(m, "boom", "machine");
  s.boom_mass_kg = f.number(b, "mass_kg", "machine.boom", 1e3, 1e6);
  s.boom_length_m = f.number(b, "length_m", "machine.boom", 5.0, 150.0);
  s.boom_half_width_m = f.number(b, "half_width_m", "machine.boom", 0.1, 10.0);
  s.boom_foot_m = f.vector3(f.required(b, "foot_m", "machine.boom"), "machine.boom.foot_m", 50.0);
  s.boom_min_angle_rad = f.number(b, "min_angle_deg", "machine.boom", 0.0, 85.0) * std::numbers::pi / 180.0;
  s.boom_max_angle_rad = f.number(b, "max_angle_deg", "machine.boom", 0.0, 89.0) * std::numbers::pi / 180.0;
  if (s.boom_max_angle_rad <= s.boom_min_angle_rad + 0.05)
    f.fail(b["max_angle_deg"], "machine.boom.max_angle_deg", "must exceed min_angle_deg by 3 degrees");
  // luffing: [house, boom], one drum, every rope reaching the boom (it holds it up)
  s.luffing = read_reeving_file(f, b, "luffing_reeving", "machine.boom", folder, {"house", "boom"}, 1);
  check_ropes_pass(f, b["luffing_reeving"], "machine.boom.luffing_reeving", s.luffing, 1,
                   "passes nothing on the boom, so it cannot hold it");

  const YAML::Node g = f.required_map(m, "grab", "machine");
  const std::string at = "machine.grab";
  // hoist: [house, boom, grab_head, grab_lower], the holding drum then the closing drum, every rope over the
  // boom head
  s.hoist =
      read_reeving_file(f, g, "hoist_reeving", at, folder, {"house", "boom", "grab_head", "grab_lower"}, 2);
  check_ropes_pass(f, g["hoist_reeving"], at + ".hoist_reeving", s.hoist, 1,
                   "passes nothing on the boom head, so it cannot carry the grab");
  s.grab_head_mass_kg = f.number(g, "head_mass_kg", at, 100.0, 1e5);
  s.grab_lower_mass_kg = f.number(g, "lower_mass_kg", at, 100.0, 2e5);
  s.grab_head_half_extents_m =
      f.vector3(f.required(g, "head_half_extents_m", at), at + ".head_half_extents_m", 5.0);
  s.grab_lower_half_extents_m =
      f.vector3(f.required(g, "lower_half_extents_m", at), at + ".lower_half_extents_m", 5.0);
  for (const auto& [half, key] : {std::pair{s.grab_head_half_extents_m, "head_half_extents_m"},
                                  std::pair{s.grab_lower_half_extents_m, "lower_half_extents_m"}})
    if (!(half.x >= 0.1 && half.y >= 0.1 && half.z >= 0.1))
      f.fail(g[key], at + "." + key, "must be at least 0.1 m each");
  s.grab_closed_gap_m = f.number(g, "closed_gap_m", at, 0.1, 10.0);
  s.grab_open_gap_m = f.number(g, "open_gap_m", at, 0.1, 10.0);
  if (s.grab_open_gap_m < s.grab_closed_gap_m + 0.2)
    f.fail(g["open_gap_m"], at + ".open_gap_m", "must exceed closed_gap_m by 0.2 m (the shells' travel)");
  s.grab.width_m = f.number(g, "width_m", at, 0.5, 10.0);
  s.grab.max_opening_m = f.number(g, "max_opening_m", at, 0.5, 15.0);
  s.grab.capacity_m3 = f.number(g, "capacity_m3", at, 0.5, 100.0);
  s.grab.sinking_speed_mps = f.number(g, "sinking_speed_mps", at, 0.0, 5.0, true);
  s.grab.max_depth_m = f.number(g, "max_depth_m", at, 0.0, 10.0, true);
  s.grab.spill_speed_mps = f.number(g, "spill_speed_mps", at, 0.0, 20.0, true);
  const YAML::Node limits = f.required(g, "hoist_limits_m", at);
  if (!limits.IsSequence() || limits.size() != 2)
    f.fail(limits, at + ".hoist_limits_m", "is [lower, upper] in metres");
  s.hoist_lower_limit_m = f.number_at(limits[0], at + ".hoist_limits_m[0]");
  s.hoist_upper_limit_m = f.number_at(limits[1], at + ".hoist_limits_m[1]");
  if (!(s.hoist_lower_limit_m >= -100.0 && s.hoist_upper_limit_m <= 200.0 &&
        s.hoist_upper_limit_m > s.hoist_lower_limit_m + 1.0))
    f.fail(limits, at + ".hoist_limits_m", "lower >= -100, upper <= 200 and 1 m above lower");

  if (const auto k = f.optional_map(m, "hook", "machine")) {
    // the hook block on the same winches: [house, boom, hook], the holding drum then the closing drum
    const std::string hat = "machine.hook";
    sim::MhcHookSettings hook;
    hook.hoist = read_reeving_file(f, *k, "hoist_reeving", hat, folder, {"house", "boom", "hook"}, 2);
    check_ropes_pass(f, (*k)["hoist_reeving"], hat + ".hoist_reeving", hook.hoist, 1,
                     "passes nothing on the boom head, so it cannot carry the hook");
    hook.block_mass_kg = f.number(*k, "block_mass_kg", hat, 100.0, 1e5);
    hook.block_half_extents_m =
        f.vector3(f.required(*k, "block_half_extents_m", hat), hat + ".block_half_extents_m", 5.0);
    const core::Vec3& half = hook.block_half_extents_m;
    if (!(half.x >= 0.1 && half.y >= 0.1 && half.z >= 0.1))
      f.fail((*k)["block_half_extents_m"], hat + ".block_half_extents_m", "must be at least 0.1 m each");
    hook.slinger_reach_m = f.number(*k, "slinger_reach_m", hat, 0.1, 5.0);
    hook.sling_length_m = f.number(*k, "sling_length_m", hat, 0.5, 30.0);
    hook.tag_line_damping_ratio = f.number(*k, "tag_line_damping_ratio", hat, 0.0, 1.0);
    hook.capacity_chart = read_capacity_chart(f, *k, hat);
    s.hook = std::move(hook);
  }

  const YAML::Node l = f.required_map(m, "load_moment_limiter", "machine");
  const std::string lat = "machine.load_moment_limiter";
  s.capacity_chart = read_capacity_chart(f, l, lat);
  s.limiter_slow_from = f.number(l, "slow_from", lat, 0.5, 1.0, false, true);
  s.limiter_filter_s = f.number(l, "filter_s", lat, 0.0, 10.0, true);

  const CabFields cab = read_cab(f, m, 100.0);
  s.cab_position_m = cab.position_m;
  s.eye_m = cab.eye_m;
  s.sight = cab.sight;
  s.controls = read_control_table(f, m, "machine");
  require_controls(f, m, s.controls,
                   {{"slew", sim::ControlKind::kAxis},
                    {"luff", sim::ControlKind::kAxis},
                    {"hoist", sim::ControlKind::kAxis},
                    {"grab", sim::ControlKind::kAxis},
                    {"emergency_stop", sim::ControlKind::kButton},
                    {"horn", sim::ControlKind::kButton}});
  if (s.hook && s.controls.find("sling") < 0)
    f.fail(m["controls"], "machine.controls",
           "a machine with a hook needs a 'sling' button (the slinger's call)");
  if (const int sling = s.controls.find("sling");
      sling >= 0 && s.controls[sling].kind != sim::ControlKind::kButton)
    f.fail(m["controls"], "machine.controls", "'sling' must be a button");
  return s;
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

// A wheeled machine's or trailer's axles (`path`.axles).
std::vector<sim::AxleSettings> read_axles(const YamlFile& f, const YAML::Node& m, const std::string& path) {
  std::vector<sim::AxleSettings> out;
  const YAML::Node axles = f.sequence(m, "axles", path, 8);
  if (axles.size() < 1) f.fail(axles, path + ".axles", "needs an axle");
  for (std::size_t n = 0; n < axles.size(); ++n) {
    const std::string at = path + ".axles[" + std::to_string(n) + "]";
    sim::AxleSettings a;
    a.x_m = f.number(axles[n], "x_m", at, -20.0, 20.0);
    a.half_track_m = f.number(axles[n], "half_track_m", at, 0.3, 5.0);
    a.hub_z_m = f.number(axles[n], "hub_z_m", at, -5.0, 5.0);
    a.steered = f.flag(axles[n], "steered", at, false);
    a.driven = f.flag(axles[n], "driven", at, false);
    a.tyres_per_side = f.integer(axles[n], "tyres_per_side", at, 1, 4);
    out.push_back(a);
  }
  return out;
}

// A tyre (`path`.tyre).
sim::TyreSettings read_tyre(const YamlFile& f, const YAML::Node& m, const std::string& path) {
  sim::TyreSettings tyre;
  const YAML::Node t = f.required_map(m, "tyre", path);
  const std::string tat = path + ".tyre";
  tyre.radius_m = f.number(t, "radius_m", tat, 0.05, 2.0);
  tyre.vertical_stiffness_n_per_m = f.number(t, "vertical_stiffness_n_per_m", tat, 1e4, 1e8);
  tyre.vertical_damping_ns_per_m = f.number(t, "vertical_damping_ns_per_m", tat, 0.0, 1e7, true);
  tyre.cornering_stiffness_n_per_rad = f.number(t, "cornering_stiffness_n_per_rad", tat, 1e3, 1e7);
  tyre.rolling_resistance = f.number(t, "rolling_resistance", tat, 0.0, 0.2, true);
  tyre.friction = f.number(t, "friction", tat, 0.05, 2.0);
  return tyre;
}

// An engine and automatic gearbox (machine.drivetrain).
sim::DrivetrainSettings read_drivetrain(const YamlFile& f, const YAML::Node& m) {
  sim::WheeledChassisSettings w;
  const YAML::Node d = f.required_map(m, "drivetrain", "machine");
  const std::string dat = "machine.drivetrain";
  const YAML::Node curve = f.sequence(d, "torque_curve", dat, 50);
  if (curve.size() < 2)
    f.fail(d["torque_curve"], dat + ".torque_curve", "needs at least two [rpm, N m] points");
  w.drivetrain.torque_curve.clear();
  for (std::size_t n = 0; n < curve.size(); ++n) {
    const std::string p = dat + ".torque_curve[" + std::to_string(n) + "]";
    if (!curve[n].IsSequence() || curve[n].size() != 2) f.fail(curve[n], p, "is [rpm, N m]");
    const double rpm = f.number_at(curve[n][0], p + "[0]"), torque = f.number_at(curve[n][1], p + "[1]");
    if (!(rpm > 0.0 && rpm < 20000.0 && torque >= 0.0 && torque < 1e5))
      f.fail(curve[n], p, "rpm 0-20000, 0-100000 N m");
    if (!w.drivetrain.torque_curve.empty() && rpm <= w.drivetrain.torque_curve.back().first)
      f.fail(curve[n], p, "engine speeds must increase down the curve");
    w.drivetrain.torque_curve.emplace_back(rpm, torque);
  }
  const YAML::Node gears = f.sequence(d, "gear_ratios", dat, 20);
  if (gears.size() < 1) f.fail(d["gear_ratios"], dat + ".gear_ratios", "needs a gear");
  w.drivetrain.gear_ratios.clear();
  for (std::size_t n = 0; n < gears.size(); ++n) {
    const std::string p = dat + ".gear_ratios[" + std::to_string(n) + "]";
    const double ratio = f.number_at(gears[n], p);
    if (!(ratio > 0.05 && ratio < 50.0)) f.fail(gears[n], p, "a ratio 0.05-50");
    w.drivetrain.gear_ratios.push_back(ratio);
  }
  w.drivetrain.final_drive = f.number(d, "final_drive", dat, 0.5, 50.0);
  w.drivetrain.efficiency = f.number(d, "efficiency", dat, 0.1, 1.0);
  w.drivetrain.converter_stall_ratio =
      f.number_or(d, "converter_stall_ratio", dat, w.drivetrain.converter_stall_ratio, 1.0, 5.0);
  return w.drivetrain;
}

// A driven and steered machine's wheels (machine.axles, tyre, drivetrain, brake_torque_per_wheel_nm,
// max_steer_deg).
sim::WheeledChassisSettings read_wheels(const YamlFile& f, const YAML::Node& m) {
  sim::WheeledChassisSettings w;
  w.axles = read_axles(f, m, "machine");
  const bool steered = std::any_of(w.axles.begin(), w.axles.end(), [](const auto& a) { return a.steered; });
  const bool driven = std::any_of(w.axles.begin(), w.axles.end(), [](const auto& a) { return a.driven; });
  if (!steered || !driven) f.fail(m["axles"], "machine.axles", "needs a steered and a driven axle");
  if (w.axles.size() < 2) f.fail(m["axles"], "machine.axles", "needs at least two axles");
  w.tyre = read_tyre(f, m, "machine");
  w.drivetrain = read_drivetrain(f, m);
  w.brake_torque_per_wheel_nm = f.number(m, "brake_torque_per_wheel_nm", "machine", 0.0, 1e6);
  w.max_steer_rad = core::deg_to_rad(f.number(m, "max_steer_deg", "machine", 1.0, 80.0));
  return w;
}

// A vehicle's driving controls: steering wheel, pedals, the direction selector (reverse, neutral, forward),
// emergency stop and horn.
void require_driving_controls(const YamlFile& f, const YAML::Node& m, const sim::ControlTable& controls) {
  using K = sim::ControlKind;
  require_controls(f, m, controls,
                   {{"steer", K::kAxis},
                    {"throttle", K::kAxis},
                    {"brake", K::kAxis},
                    {"direction", K::kSwitch},
                    {"emergency_stop", K::kButton},
                    {"horn", K::kButton}});
  if (controls[controls.find("direction")].positions !=
      std::vector<std::string>{"reverse", "neutral", "forward"})
    f.fail(m["controls"], "machine.controls",
           "'direction' must have the positions [reverse, neutral, forward]");
}

}  // namespace

sim::TractorSettings read_tractor(const YamlFile& f) {
  sim::TractorSettings s;
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  if (const std::string kind = f.text(m, "kind", "machine"); kind != "tractor")
    f.fail(m["kind"], "machine.kind", "this is a tractor file (kind: tractor), not a '" + kind + "'");
  f.text(m, "name", "machine");
  std::tie(s.mass_kg, s.half_extents_m) = read_chassis_box(f, m, 500.0, 1e5);
  s.chassis = read_wheels(f, m);
  s.steer_rate_per_s = f.number(m, "steer_rate_per_s", "machine", 0.05, 20.0);
  const CabFields cab = read_cab(f, m, 20.0);
  s.cab_position_m = cab.position_m;
  s.eye_m = cab.eye_m;
  s.sight = cab.sight;
  s.controls = read_control_table(f, m, "machine");
  require_driving_controls(f, m, s.controls);
  require_controls(f, m, s.controls, {{"couple", sim::ControlKind::kButton}});
  return s;
}

sim::MhcSettings load_mhc(const YamlFile& f, const std::string& folder) {
  sim::MhcSettings s = read_mhc(f, folder);
  f.check_unknown_keys();
  return s;
}

sim::MhcSettings load_mhc(const std::string& path) {
  return load_mhc(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

sim::StsCraneSettings load_sts_crane(const YamlFile& f, const std::string& folder) {
  sim::StsCraneSettings s = read_sts_crane(f, folder);
  f.check_unknown_keys();
  return s;
}

sim::StsCraneSettings load_sts_crane(const std::string& path) {
  return load_sts_crane(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

sim::TractorSettings load_tractor(const YamlFile& f) {
  sim::TractorSettings s = read_tractor(f);
  f.check_unknown_keys();
  return s;
}

sim::TractorSettings load_tractor(const std::string& path) {
  return load_tractor(YamlFile::load(path));
}

sim::TrailerSettings load_trailer(const YamlFile& f) {
  sim::TrailerSettings s;
  const YAML::Node t = f.required_map(f.root(), "trailer", "");
  const std::string kind = f.text(t, "kind", "trailer");
  if (kind != "mafi" && kind != "semi")
    f.fail(t["kind"], "trailer.kind", "a trailer is a mafi (roll trailer) or a semi (not '" + kind + "')");
  s.look = "trailer." + kind;
  f.text(t, "name", "trailer");
  s.mass_kg = f.number(t, "tare_kg", "trailer", 500.0, 1e5);
  s.max_payload_kg = f.number(t, "max_payload_kg", "trailer", 0.0, 2e5, true);
  s.half_extents_m =
      f.vector3(f.required(t, "deck_half_extents_m", "trailer"), "trailer.deck_half_extents_m", 15.0);
  const core::Vec3& half = s.half_extents_m;
  if (!(half.x >= 0.5 && half.y >= 0.5 && half.z >= 0.05))
    f.fail(t["deck_half_extents_m"], "trailer.deck_half_extents_m", "must be at least [0.5, 0.5, 0.05] m");
  s.kingpin_m = f.vector3(f.required(t, "kingpin_m", "trailer"), "trailer.kingpin_m", 20.0);
  s.wheels.axles = read_axles(f, t, "trailer");
  for (std::size_t n = 0; n < s.wheels.axles.size(); ++n) {
    const sim::AxleSettings& a = s.wheels.axles[n];
    const std::string at = "trailer.axles[" + std::to_string(n) + "]";
    if (a.steered || a.driven) f.fail(t["axles"][n], at, "a trailer's axles neither steer nor drive");
    if (a.x_m >= s.kingpin_m.x - 1.0) f.fail(t["axles"][n], at, "must lie behind the kingpin (at least 1 m)");
  }
  s.wheels.tyre = read_tyre(f, t, "trailer");
  s.wheels.brake_torque_per_wheel_nm = f.number(t, "brake_torque_per_wheel_nm", "trailer", 0.0, 1e6);
  if (const auto l = f.optional_map(t, "legs", "trailer")) {
    // feet that do not roll: a stiff pad held by a brake far beyond its grip
    const std::string at = "trailer.legs";
    sim::WheeledChassisSettings legs;
    sim::AxleSettings a;
    a.x_m = f.number(*l, "x_m", at, -20.0, 20.0);
    a.half_track_m = f.number(*l, "half_track_m", at, 0.1, 5.0);
    legs.tyre.radius_m = 0.1;
    legs.tyre.vertical_stiffness_n_per_m = 2.0e6;
    legs.tyre.vertical_damping_ns_per_m = 4.0e4;
    legs.tyre.cornering_stiffness_n_per_rad = 5.0e5;
    legs.tyre.rolling_resistance = 0.0;
    legs.tyre.friction = f.number(*l, "friction", at, 0.05, 2.0);
    a.hub_z_m = f.number(*l, "foot_z_m", at, -5.0, 5.0) + legs.tyre.radius_m;
    legs.axles = {a};
    legs.brake_torque_per_wheel_nm = 1e7;
    s.legs = legs;
  }
  f.check_unknown_keys();
  return s;
}

sim::TrailerSettings load_trailer(const std::string& path) {
  return load_trailer(YamlFile::load(path));
}

namespace {

// A hydraulic motion (`at`.`key`): its travel, speed, ramp and force; rotary ones in degrees and N m. The
// cylinders hold the load on their valves (the brake: three times the force) and stop in a quarter of the
// ramp at an emergency stop.
sim::DriveSettings read_hydraulics(const YamlFile& f, const YAML::Node& parent, const std::string& key,
                                   const std::string& at, bool rotary, double max_force) {
  const YAML::Node n = f.required_map(parent, key, at);
  const std::string p = at + "." + key;
  const double unit = rotary ? core::deg_to_rad(1.0) : 1.0;
  const char* min_key = rotary ? "min_deg" : "min_m";
  const char* max_key = rotary ? "max_deg" : "max_m";
  const double range = rotary ? 360.0 : 50.0;
  sim::DriveSettings d;
  d.min_position_m = f.number(n, min_key, p, -range, range) * unit;
  d.max_position_m = f.number(n, max_key, p, -range, range) * unit;
  if (d.max_position_m <= d.min_position_m)
    f.fail(n[max_key], p + "." + max_key, std::string("must exceed ") + min_key);
  d.max_speed_mps =
      f.number(n, rotary ? "speed_deg_s" : "speed_mps", p, 0.0, rotary ? 90.0 : 5.0, true) * unit;
  const double ramp_s = f.number(n, "ramp_s", p, 0.05, 10.0);
  d.acceleration_mps2 = d.deceleration_mps2 = d.max_speed_mps / ramp_s;
  d.emergency_deceleration_mps2 = 4.0 * d.acceleration_mps2;
  d.max_force_n = f.number(n, rotary ? "torque_nm" : "force_n", p, 0.0, max_force, true);
  d.brake_force_n = 3.0 * d.max_force_n;
  return d;
}

}  // namespace

sim::ReachStackerSettings load_reach_stacker(const YamlFile& f) {
  sim::ReachStackerSettings s;
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  if (const std::string kind = f.text(m, "kind", "machine"); kind != "reach_stacker")
    f.fail(m["kind"], "machine.kind",
           "this is a reach stacker file (kind: reach_stacker), not a '" + kind + "'");
  f.text(m, "name", "machine");
  std::tie(s.mass_kg, s.half_extents_m) = read_chassis_box(f, m, 1000.0, 3e5);
  s.chassis = read_wheels(f, m);
  if (sim::tipping_axle_x_m(s) <= 0.0)
    f.fail(m["axles"], "machine.axles", "the front axle must lie ahead of the centre of mass");
  s.steer_rate_per_s = f.number(m, "steer_rate_per_s", "machine", 0.05, 20.0);
  const YAML::Node b = f.required_map(m, "boom", "machine");
  const std::string bat = "machine.boom";
  s.boom_mass_kg = f.number(b, "mass_kg", bat, 100.0, 1e5);
  s.boom_pivot_m = f.vector3(f.required(b, "pivot_m", bat), bat + ".pivot_m", 20.0);
  s.boom_length_m = f.number(b, "length_m", bat, 1.0, 40.0);
  s.luff = read_hydraulics(f, b, "lift", bat, true, kMaxForce_n);
  if (s.luff.min_position_m < -core::deg_to_rad(30.0) || s.luff.max_position_m > core::deg_to_rad(80.0))
    f.fail(b["lift"], bat + ".lift", "the boom works between -30 and 80 deg");
  s.telescope = read_hydraulics(f, b, "telescope", bat, false, kMaxForce_n);
  if (s.telescope.min_position_m != 0.0)
    f.fail(b["telescope"], bat + ".telescope.min_m", "the telescope's travel starts at 0 (in)");
  s.spreader_mass_kg = f.number(m, "spreader_mass_kg", "machine", 100.0, 5e4);
  s.spreader = read_spreader(f, m);
  if (sim::rotator_mass_kg(s) < 200.0)
    f.fail(m["spreader"], "machine.spreader.mass_kg",
           "leaves less than 200 kg of spreader_mass_kg for the rotator between it and the boom");
  const YAML::Node r = f.required_map(m, "rotator", "machine");
  const std::string rat = "machine.rotator";
  s.head_drop_m = f.number(r, "head_drop_m", rat, 0.8 + 0.5 * s.spreader.height_m, 5.0);
  s.tilt_damping_nms_per_rad = f.number(r, "tilt_damping_nms_per_rad", rat, 0.0, 1e8);
  s.rotate = read_hydraulics(f, r, "rotation", rat, true, 1e7);
  s.side_shift = read_hydraulics(f, r, "side_shift", rat, false, 1e7);
  const YAML::Node t = f.required_map(m, "twistlocks", "machine");
  s.twistlocks.lateral_tolerance_m = f.number(t, "lateral_tolerance_m", "machine.twistlocks", 0.0, 1.0, true);
  s.twistlocks.landed_gap_m = f.number(t, "landed_gap_m", "machine.twistlocks", 0.0, 1.0, true);
  const YAML::Node l = f.required_map(m, "load_chart", "machine");
  const std::string lat = "machine.load_chart";
  const YAML::Node rows = f.sequence(l, "row_reach_m", lat, 6);
  if (rows.size() < 1) f.fail(l["row_reach_m"], lat + ".row_reach_m", "needs a row");
  s.row_reach_m.clear();
  for (std::size_t n = 0; n < rows.size(); ++n) {
    const std::string p = lat + ".row_reach_m[" + std::to_string(n) + "]";
    const double reach = f.number_at(rows[n], p);
    if (!(reach > 0.5 && reach < 30.0)) f.fail(rows[n], p, "a reach of 0.5-30 m");
    if (!s.row_reach_m.empty() && reach <= s.row_reach_m.back())
      f.fail(rows[n], p, "rows must lie further out");
    s.row_reach_m.push_back(reach);
  }
  s.rated_limit_kg = f.number(l, "rated_limit_kg", lat, 1000.0, 2e5);
  s.stability_margin = f.number(l, "stability_margin", lat, 1.0, 3.0);
  s.warn_from = f.number(l, "warn_from", lat, 0.5, 1.0);
  s.load_filter_s = f.number(l, "load_filter_s", lat, 0.01, 10.0);
  if (sim::tipping_load_kg(s, s.row_reach_m.back()) <= 0.0)
    f.fail(l["row_reach_m"], lat + ".row_reach_m",
           "the machine tips over with nothing on it at its last row");
  s.tip_over_rad = core::deg_to_rad(f.number(m, "tip_over_deg", "machine", 1.0, 45.0));
  const CabFields cab = read_cab(f, m, 20.0);
  s.cab_position_m = cab.position_m;
  s.eye_m = cab.eye_m;
  s.sight = cab.sight;
  s.controls = read_control_table(f, m, "machine");
  using K = sim::ControlKind;
  require_driving_controls(f, m, s.controls);
  require_controls(f, m, s.controls,
                   {{"boom", K::kAxis},
                    {"telescope", K::kAxis},
                    {"rotate", K::kAxis},
                    {"side_shift", K::kAxis},
                    {"lock", K::kButton},
                    {"unlock", K::kButton},
                    {"spreader_20", K::kButton},
                    {"spreader_40", K::kButton}});
  f.check_unknown_keys();
  return s;
}

sim::ReachStackerSettings load_reach_stacker(const std::string& path) {
  return load_reach_stacker(YamlFile::load(path));
}

sim::RtgSettings load_rtg(const YamlFile& f, const std::string& folder) {
  sim::RtgSettings s;
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  if (const std::string kind = f.text(m, "kind", "machine"); kind != "rtg")
    f.fail(m["kind"], "machine.kind", "this is an RTG file (kind: rtg), not a '" + kind + "'");
  f.text(m, "name", "machine");
  const YAML::Node g = f.required_map(m, "gantry", "machine");
  const std::string gat = "machine.gantry";
  // RTGs weigh 120-200 t unladen (reference.md); the structure without its trolley
  s.frame_mass_kg = f.number(g, "mass_kg", gat, 2e4, 5e5);
  s.frame_centre_height_m = f.number(g, "centre_of_mass_height_m", gat, 1.0, 40.0);
  s.span_m = f.number(g, "span_m", gat, 5.0, 60.0);
  s.wheelbase_m = f.number(g, "wheelbase_m", gat, 2.0, 30.0);
  s.bogie_tyre_spacing_m = f.number(g, "bogie_tyre_spacing_m", gat, 0.5, s.wheelbase_m - 0.5);
  s.sill_height_m = f.number(g, "sill_height_m", gat, 0.3, 5.0);
  s.leg_width_m = f.number(g, "leg_width_m", gat, 0.3, 4.0);
  s.wind_area_across_m2 = f.number(g, "wind_area_across_m2", gat, 1.0, 2000.0);
  s.wind_area_along_m2 = f.number(g, "wind_area_along_m2", gat, 1.0, 2000.0);
  s.gantry_drive = read_drive(f, g, gat);
  s.gantry_loaded_speed_mps = f.number(g, "loaded_speed_mps", gat, 0.0, s.gantry_drive.max_speed_mps, true);
  s.max_steer_rad = core::deg_to_rad(f.number(g, "max_steer_deg", gat, 0.0, 20.0, true));
  s.wheel_turn_time_s = f.number(g, "wheel_turn_time_s", gat, 1.0, 600.0);
  s.tyre = read_tyre(f, g, gat);
  if (s.tyre.radius_m >= s.sill_height_m)
    f.fail(g["sill_height_m"], gat + ".sill_height_m", "the sills must clear the tyres (tyre.radius_m)");
  const YAML::Node t = f.required_map(m, "trolley", "machine");
  const std::string tat = "machine.trolley";
  s.trolley_mass_kg = f.number(t, "mass_kg", tat, 1000.0, 2e5);
  s.trolley_rail_height_m = f.number(t, "rail_height_m", tat, s.sill_height_m + 5.0, 60.0);
  s.trolley_drive = read_drive(f, t, tat);
  check_drive_moves(f, t, tat, s.trolley_drive, s.trolley_mass_kg, "the trolley");
  check_drive_moves(f, g, gat, s.gantry_drive, s.frame_mass_kg + s.trolley_mass_kg, "the crane");
  if (s.trolley_drive.min_position_m < -0.5 * s.span_m || s.trolley_drive.max_position_m > 0.5 * s.span_m)
    f.fail(t["drive"], tat + ".drive", "the trolley runs between the legs (within half the span)");
  s.rig = read_spreader_hoist(f, m, folder, {"trolley", "headblock"}, s.trolley_rail_height_m);
  const CabFields cab = read_cab(f, m, 10.0);
  s.cab_position_m = cab.position_m;
  s.eye_m = cab.eye_m;
  s.sight = cab.sight;
  s.controls = read_control_table(f, m, "machine");
  try {
    const sim::RtgControlSlots slots(s.controls);  // every control the RTG reads, of its kind
  } catch (const std::invalid_argument& e) {
    f.fail(m["controls"], "machine.controls", e.what());
  }
  f.check_unknown_keys();
  return s;
}

sim::RtgSettings load_rtg(const std::string& path) {
  return load_rtg(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

std::string machine_file_kind(const std::string& path) {
  const YamlFile f = YamlFile::load(path);
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  const std::string kind = f.text(m, "kind", "machine");
  if (!sim::find_machine_type(kind)) {
    std::string kinds;
    for (const sim::MachineType* type : sim::machine_types())
      kinds += std::string(kinds.empty() ? "" : ", ") + type->kind;
    f.fail(m["kind"], "machine.kind", "a machine is one of: " + kinds + " (not '" + kind + "')");
  }
  return kind;
}

}  // namespace harbour::io
