#include "harbour/machines/rtg/Files.h"

#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/machines/parts/PartFiles.h"

namespace harbour::io {
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
  check_machine_file_sections(f);
  f.check_unknown_keys();
  return s;
}

sim::RtgSettings load_rtg(const std::string& path) {
  return load_rtg(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

namespace {

StartPoseForm start_form(const sim::RtgSetup& rtg) {
  const sim::RtgSettings& c = rtg.crane;
  StartPoseForm form = pose_on_the_quay("crane");
  form.fields.push_back(pose_optional_field("heading_deg", 0.0, -360.0, 360.0));
  form.fields.push_back(
      pose_number_field("trolley_x_m", c.trolley_drive.min_position_m, c.trolley_drive.max_position_m));
  form.fields.push_back(pose_number_field("spreader_z_m", 1.0, c.trolley_rail_height_m - 2.0));
  form.fields.push_back(pose_optional_field("steer_bias_deg", 0.0, -2.0, 2.0));
  return form;
}

// the RTG stands over its block, its wheels along it
sim::MachineSetup read_setup(const std::string& path, const StartBlock& start) {
  sim::RtgSetup rtg;
  rtg.crane = load_rtg(path);
  const StartPoseForm form = start_form(rtg);
  rtg.start.position_m = start.position();
  rtg.start.heading_rad = core::deg_to_rad(start.number(form, "heading_deg"));
  rtg.start.trolley_x_m = start.number(form, "trolley_x_m");
  rtg.start.spreader_z_m = start.number(form, "spreader_z_m");
  rtg.start.steer_bias_rad = core::deg_to_rad(start.number(form, "steer_bias_deg"));
  return rtg;
}

}  // namespace

const MachineFileType& rtg_machine_files() {
  static constexpr MachineFileType type{"rtg", "crane", &read_setup,
                                        &start_pose_form_of<sim::RtgSetup, &start_form>};
  return type;
}

}  // namespace harbour::io
