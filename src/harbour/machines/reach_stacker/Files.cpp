#include "harbour/machines/reach_stacker/Files.h"

#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/machines/parts/PartFiles.h"

namespace harbour::io {
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
  using K = scene::ControlKind;
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
  check_machine_file_sections(f);
  f.check_unknown_keys();
  return s;
}

sim::ReachStackerSettings load_reach_stacker(const std::string& path) {
  return load_reach_stacker(YamlFile::load(path));
}

namespace {

StartPoseForm start_form(const sim::ReachStackerSetup& stacker) {
  const sim::ReachStackerSettings& v = stacker.vehicle;
  StartPoseForm form = pose_on_the_quay("vehicle");
  form.fields.push_back(pose_number_field("heading_deg", -360.0, 360.0));
  form.fields.push_back(pose_number_field("boom_deg", core::rad_to_deg(v.luff.min_position_m),
                                          core::rad_to_deg(v.luff.max_position_m)));
  form.fields.push_back(pose_optional_field("extension_m", 0.0, 0.0, v.telescope.max_position_m));
  return form;
}

// it stands on the quay, its boom set
sim::MachineSetup read_setup(const std::string& path, const StartBlock& start) {
  sim::ReachStackerSetup stacker;
  stacker.vehicle = load_reach_stacker(path);
  const StartPoseForm form = start_form(stacker);
  stacker.start.position_m = start.position();
  stacker.start.heading_rad = core::deg_to_rad(start.number(form, "heading_deg"));
  stacker.start.boom_rad = core::deg_to_rad(start.number(form, "boom_deg"));
  stacker.start.extension_m = start.number(form, "extension_m");
  return stacker;
}

}  // namespace

const MachineFileType& reach_stacker_machine_files() {
  static constexpr MachineFileType type{"reach_stacker", "vehicle", &read_setup,
                                        &start_pose_form_of<sim::ReachStackerSetup, &start_form>};
  return type;
}

}  // namespace harbour::io
