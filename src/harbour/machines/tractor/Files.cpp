#include "harbour/machines/tractor/Files.h"

#include <filesystem>

#include "harbour/core/StateHash.h"
#include "harbour/core/Units.h"
#include "harbour/io/ControlFiles.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/parts/PartFiles.h"

namespace harbour::io {
namespace {

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
  require_controls(f, m, s.controls, {{"couple", scene::ControlKind::kButton}});
  return s;
}

}  // namespace

sim::TractorSettings load_tractor(const YamlFile& f) {
  sim::TractorSettings s = read_tractor(f);
  check_machine_file_sections(f);
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

// The trailer a tractor starts coupled to (`at`: {id, file, payload_kg}), checked to stand level on its
// plate.
sim::TrailerSettings read_coupled_trailer(const YamlFile& f, const YAML::Node& t, const std::string& at,
                                          const std::string& folder, const sim::TractorSettings& tractor) {
  const std::string file = f.text(t, "file", at);
  const std::string path = (std::filesystem::path(folder) / file).lexically_normal().string();
  if (!std::filesystem::is_regular_file(path)) f.fail(t["file"], at + ".file", "no such file: " + path);
  sim::TrailerSettings trailer = load_trailer(path);
  trailer.id = f.text(t, "id", at);
  // the payload's centre along the deck (a load over the axle leaves little on the kingpin)
  // (one that receives a box handed over starts empty)
  const bool receives = f.optional(t, "receives", at).has_value();
  const double payload_kg = receives ? 0.0 : f.number(t, "payload_kg", at, 0.0, trailer.max_payload_kg, true);
  const double payload_x_m =
      f.number_or(t, "payload_centre_m", at, 0.0, -trailer.half_extents_m.x, trailer.half_extents_m.x);
  trailer.center_of_mass_x_m = payload_kg * payload_x_m / (trailer.mass_kg + payload_kg);
  trailer.mass_kg += payload_kg;
  if (payload_kg > 0.0)  // drawn as the longest ISO box its deck holds (its mass is the payload's)
    for (const char* type : {"40ft", "20ft"})
      if (const core::Vec3 size = iso_types().at(type).size_m;
          size.x <= 2.0 * trailer.half_extents_m.x + 0.05) {
        trailer.payload_half_extents_m = size * 0.5;
        // its ISO code painted on its sides, a serial of the trailer's name (the same every run)
        core::StateHash name;
        name.add_bytes(trailer.id.data(), trailer.id.size());
        trailer.payload_id = iso6346_code("HBSU", static_cast<int>(name.value() % 1000000u));
        break;
      }
  // a box a team's crane will hand over onto it (its ISO type)
  if (receives) {
    const std::string type = f.text(t, "receives", at);
    const auto iso = iso_types().find(type);
    if (iso == iso_types().end())
      f.fail(t["receives"], at + ".receives",
             "unknown container type '" + type + "' (20ft, 40ft, 40ftHC, 45ftHC)");
    if (f.optional(t, "payload_kg", at))
      f.fail(t["payload_kg"], at + ".payload_kg",
             "a trailer that receives a box starts empty (no payload_kg)");
    trailer.receives_half_extents_m = iso->second.size_m * 0.5;
  }
  // level when coupled: its kingpin as high as the plate, up; its legs clear then and down with the plate
  const sim::AxleSettings& front = tractor.chassis.axles.front();
  const double plate_m = tractor.chassis.tyre.radius_m - front.hub_z_m + tractor.hitch_m.z;
  const sim::AxleSettings& axle = trailer.wheels.axles.front();
  const double centre_m = trailer.wheels.tyre.radius_m - axle.hub_z_m;
  const double kingpin_m = centre_m + trailer.kingpin_m.z;
  const auto metres = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", v);
    return std::string(text);
  };
  if (std::abs(kingpin_m - plate_m) > 0.15)
    f.fail(t["file"], at + ".file",
           "its kingpin stands " + metres(kingpin_m) + " m high on its wheels, the tractor's plate " +
               metres(plate_m) + " m: it would not ride level");
  if (trailer.legs) {
    const sim::AxleSettings& legs = trailer.legs->axles.front();
    const double foot_m = centre_m + legs.hub_z_m - trailer.legs->tyre.radius_m;
    const double drop_m =
        tractor.fifth_wheel.lift_m * (legs.x_m - axle.x_m) / (trailer.kingpin_m.x - axle.x_m);
    if (foot_m < 0.02 || foot_m > drop_m - 0.03)
      f.fail(t["file"], at + ".file",
             "its legs stand " + metres(foot_m) +
                 " m clear when coupled: they must clear the ground and reach it as the plate lowers (" +
                 metres(drop_m) + " m there)");
  }
  return trailer;
}

StartPoseForm start_form(const sim::TractorSetup&) {
  StartPoseForm form = pose_on_the_quay("vehicle");
  form.fields.push_back(pose_number_field("heading_deg", -360.0, 360.0));
  return form;
}

// the vehicle stands on the quay, perhaps with a trailer coupled
sim::MachineSetup read_setup(const std::string& path, const StartBlock& start) {
  sim::TractorSetup tractor;
  tractor.vehicle = load_tractor(path);
  const StartPoseForm form = start_form(tractor);
  tractor.start.position_m = start.position();
  tractor.start.heading_rad = core::deg_to_rad(start.number(form, "heading_deg"));
  if (const auto t = start.file.optional_map(start.node, "trailer", start.at))
    tractor.start.trailer =
        read_coupled_trailer(start.file, *t, start.at + ".trailer", start.folder, tractor.vehicle);
  return tractor;
}

}  // namespace

const MachineFileType& tractor_machine_files() {
  static constexpr MachineFileType type{"tractor", "vehicle", &read_setup,
                                        &start_pose_form_of<sim::TractorSetup, &start_form>};
  return type;
}

}  // namespace harbour::io
