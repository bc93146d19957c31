#include "harbour/machines/parts/PartFiles.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ReevingFiles.h"

namespace harbour::io {

// `turns`: a rotary axis without end switches (slewing): no positions read
sim::DriveSettings read_drive(const YamlFile& f, const YAML::Node& parent, const std::string& at,
                              bool turns) {
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

namespace {

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

}  // namespace

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
    a.hub_z_m = f.number(axles[n], "hub_z_m", at, -10.0, 5.0);  // a portal's centre of mass high above them
    a.steered = f.flag(axles[n], "steered", at, false);
    a.driven = f.flag(axles[n], "driven", at, false);
    a.parking_braked = f.flag(axles[n], "parking_brake", at, false);
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

namespace {

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

}  // namespace

// A driven and steered machine's wheels (machine.axles, tyre, drivetrain, brake_torque_per_wheel_nm,
// parking_brake_torque_per_wheel_nm, max_steer_deg).
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
  w.parking_brake_torque_per_wheel_nm = f.number(m, "parking_brake_torque_per_wheel_nm", "machine", 1.0, 1e6);
  if (std::none_of(w.axles.begin(), w.axles.end(), [](const auto& a) { return a.parking_braked; }))
    f.fail(m["axles"], "machine.axles", "needs an axle with the parking brake (parking_brake: true)");
  w.max_steer_rad = core::deg_to_rad(f.number(m, "max_steer_deg", "machine", 1.0, 80.0));
  return w;
}

}  // namespace harbour::io
