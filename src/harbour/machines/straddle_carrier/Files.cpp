#include "harbour/machines/straddle_carrier/Files.h"

#include <algorithm>
#include <filesystem>

#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/machines/parts/PartFiles.h"

namespace harbour::io {

sim::StraddleCarrierSettings load_straddle_carrier(const YamlFile& f, const std::string& folder) {
  sim::StraddleCarrierSettings s;
  const YAML::Node m = f.required_map(f.root(), "machine", "");
  if (const std::string kind = f.text(m, "kind", "machine"); kind != "straddle_carrier")
    f.fail(m["kind"], "machine.kind",
           "this is a straddle carrier file (kind: straddle_carrier), not a '" + kind + "'");
  f.text(m, "name", "machine");
  std::tie(s.mass_kg, s.half_extents_m) = read_chassis_box(f, m, 5000.0, 3e5);
  s.chassis = read_wheels(f, m);
  if (s.chassis.axles.size() < 2 ||
      std::any_of(s.chassis.axles.begin(), s.chassis.axles.end(), [](const auto& a) { return !a.steered; }))
    f.fail(m["axles"], "machine.axles", "a straddle carrier steers every wheel (each axle steered: true)");
  s.steer_rate_per_s = f.number(m, "steer_rate_per_s", "machine", 0.05, 20.0);
  const YAML::Node p = f.required_map(m, "portal", "machine");
  const std::string pat = "machine.portal";
  s.leg_x_m = f.number(p, "leg_x_m", pat, 0.5, 20.0);
  s.leg_y_m = f.number(p, "leg_y_m", pat, 1.0, 5.0);
  s.leg_width_m = f.number(p, "leg_width_m", pat, 0.1, 1.5);
  s.sill_bottom_m = f.number(p, "sill_bottom_m", pat, 0.1, 3.0);
  s.sill_top_m = f.number(p, "sill_top_m", pat, s.sill_bottom_m + 0.1, 5.0);
  s.top_frame_m = f.number(p, "top_frame_m", pat, s.sill_top_m + 3.0, 30.0);
  s.wind_area_front_m2 = f.number(p, "wind_area_front_m2", pat, 1.0, 500.0);
  s.wind_area_side_m2 = f.number(p, "wind_area_side_m2", pat, 1.0, 500.0);
  if (s.leg_y_m - 0.5 * s.leg_width_m < 1.5)
    f.fail(p["leg_y_m"], pat + ".leg_y_m",
           "the legs must clear a 2.44 m wide box between them (1.5 m each side)");
  // the sheaves hang the spreader from the top frame: its centre's height there, above the ground
  s.rig = read_spreader_hoist(f, m, folder, {"portal", "headblock"}, s.top_frame_m + 0.5);
  const CabFields cab = read_cab(f, m, 20.0);
  s.cab_position_m = cab.position_m;
  s.eye_m = cab.eye_m;
  s.sight = cab.sight;
  s.controls = read_control_table(f, m, "machine");
  require_driving_controls(f, m, s.controls);
  try {
    const sim::StraddleCarrierSlots slots(s.controls);  // every control it reads, of its kind
  } catch (const std::invalid_argument& e) {
    f.fail(m["controls"], "machine.controls", e.what());
  }
  check_machine_file_sections(f);
  f.check_unknown_keys();
  return s;
}

sim::StraddleCarrierSettings load_straddle_carrier(const std::string& path) {
  return load_straddle_carrier(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

namespace {

StartPoseForm start_form(const sim::StraddleCarrierSetup& carrier) {
  const sim::SpreaderHoistSettings& rig = carrier.vehicle.rig;
  StartPoseForm form = pose_on_the_quay("vehicle");
  form.fields.push_back(pose_number_field("heading_deg", -360.0, 360.0));
  form.fields.push_back(pose_number_field("spreader_z_m", rig.lower_limit_m, rig.upper_limit_m));
  return form;
}

// it stands on the yard, its spreader at a height between its legs
sim::MachineSetup read_setup(const std::string& path, const StartBlock& start) {
  sim::StraddleCarrierSetup carrier;
  carrier.vehicle = load_straddle_carrier(path);
  const StartPoseForm form = start_form(carrier);
  carrier.start.position_m = start.position();
  carrier.start.heading_rad = core::deg_to_rad(start.number(form, "heading_deg"));
  carrier.start.spreader_z_m = start.number(form, "spreader_z_m");
  return carrier;
}

}  // namespace

const MachineFileType& straddle_carrier_machine_files() {
  static constexpr MachineFileType type{"straddle_carrier", "vehicle", &read_setup,
                                        &start_pose_form_of<sim::StraddleCarrierSetup, &start_form>};
  return type;
}

}  // namespace harbour::io
