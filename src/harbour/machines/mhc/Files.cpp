#include "harbour/machines/mhc/Files.h"

#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/machines/parts/PartFiles.h"

namespace harbour::io {
namespace {

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
                   {{"slew", scene::ControlKind::kAxis},
                    {"luff", scene::ControlKind::kAxis},
                    {"hoist", scene::ControlKind::kAxis},
                    {"grab", scene::ControlKind::kAxis},
                    {"emergency_stop", scene::ControlKind::kButton},
                    {"horn", scene::ControlKind::kButton}});
  if (s.hook && s.controls.find("sling") < 0)
    f.fail(m["controls"], "machine.controls",
           "a machine with a hook needs a 'sling' button (the slinger's call)");
  if (const int sling = s.controls.find("sling");
      sling >= 0 && s.controls[sling].kind != scene::ControlKind::kButton)
    f.fail(m["controls"], "machine.controls", "'sling' must be a button");
  return s;
}

}  // namespace

sim::MhcSettings load_mhc(const YamlFile& f, const std::string& folder) {
  sim::MhcSettings s = read_mhc(f, folder);
  check_machine_file_sections(f);
  f.check_unknown_keys();
  return s;
}

sim::MhcSettings load_mhc(const std::string& path) {
  return load_mhc(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

namespace {

StartPoseForm start_form(const sim::MhcSetup& mhc) {
  const sim::MhcSettings& c = mhc.crane;
  StartPoseForm form = pose_on_the_quay("crane");
  form.fields.push_back(pose_number_field("slew_deg", -360.0, 360.0));
  form.fields.push_back(pose_number_field("boom_deg", core::rad_to_deg(c.boom_min_angle_rad),
                                          core::rad_to_deg(c.boom_max_angle_rad)));
  form.fields.push_back(pose_number_field(mhc.start.on_hook ? "hook_z_m" : "grab_z_m", c.hoist_lower_limit_m,
                                          c.hoist_upper_limit_m));
  return form;
}

// the MHC stands on its outriggers on the quay, on its grab (bulk) or its hook block (general cargo)
sim::MachineSetup read_setup(const std::string& path, const StartBlock& start) {
  const YamlFile& f = start.file;
  sim::MhcSetup mhc;
  mhc.crane = load_mhc(path);
  const std::string tool =
      f.optional(start.node, "tool", start.at) ? f.text(start.node, "tool", start.at) : "grab";
  if (tool != "grab" && tool != "hook") f.fail(start.node["tool"], start.at + ".tool", "is grab or hook");
  mhc.start.on_hook = tool == "hook";
  if (mhc.start.on_hook && !mhc.crane.hook)
    f.fail(start.node["tool"], start.at + ".tool", "the machine file has no hook (machine.hook)");
  const StartPoseForm form = start_form(mhc);
  mhc.start.position_m = start.position();
  mhc.start.slew_rad = core::deg_to_rad(start.number(form, "slew_deg"));
  mhc.start.boom_rad = core::deg_to_rad(start.number(form, "boom_deg"));
  mhc.start.hanging_z_m = start.number(form, mhc.start.on_hook ? "hook_z_m" : "grab_z_m");
  return mhc;
}

}  // namespace

const MachineFileType& mhc_machine_files() {
  static constexpr MachineFileType type{"mhc", "crane", &read_setup,
                                        &start_pose_form_of<sim::MhcSetup, &start_form>};
  return type;
}

}  // namespace harbour::io
