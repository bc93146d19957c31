#include "harbour/machines/sts/Files.h"

#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/machines/parts/PartFiles.h"

namespace harbour::io {
namespace {

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

}  // namespace

sim::StsCraneSettings load_sts_crane(const YamlFile& f, const std::string& folder) {
  sim::StsCraneSettings s = read_sts_crane(f, folder);
  check_machine_file_sections(f);
  f.check_unknown_keys();
  return s;
}

sim::StsCraneSettings load_sts_crane(const std::string& path) {
  return load_sts_crane(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

namespace {

StartPoseForm start_form(const sim::StsSetup& sts) {
  const sim::StsCraneSettings& c = sts.crane;
  StartPoseForm form{"crane", {}};
  form.fields.push_back(
      pose_number_field("gantry_y_m", c.gantry_drive.min_position_m, c.gantry_drive.max_position_m));
  form.fields.push_back(
      pose_number_field("trolley_x_m", c.trolley_drive.min_position_m, c.trolley_drive.max_position_m));
  form.fields.push_back(pose_number_field("spreader_z_m", 0.0, c.trolley_rail_height_m - 2.0));
  form.fields.back().exclusive_min = true;
  return form;
}

// the crane starts on its rails
sim::MachineSetup read_setup(const std::string& path, const StartBlock& start) {
  sim::StsSetup sts;
  sts.crane = load_sts_crane(path);
  const StartPoseForm form = start_form(sts);
  sts.gantry_y_m = start.number(form, "gantry_y_m");
  sts.trolley_x_m = start.number(form, "trolley_x_m");
  sts.spreader_z_m = start.number(form, "spreader_z_m");
  return sts;
}

}  // namespace

const MachineFileType& sts_machine_files() {
  static constexpr MachineFileType type{"sts", "crane", &read_setup,
                                        &start_pose_form_of<sim::StsSetup, &start_form>};
  return type;
}

}  // namespace harbour::io
