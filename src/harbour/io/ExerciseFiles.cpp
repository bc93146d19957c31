#include "harbour/io/ExerciseFiles.h"

#include <filesystem>
#include <map>

#include "harbour/core/Units.h"
#include "harbour/io/MachineFiles.h"

namespace harbour::io {
namespace {

constexpr double kHuge = 1e6;

// ISO 668 external dimensions [m] (length, width, height)
const std::map<std::string, core::Vec3>& iso_types() {
  static const std::map<std::string, core::Vec3> types = {{"20ft", {6.058, 2.438, 2.591}},
                                                          {"40ft", {12.192, 2.438, 2.591}},
                                                          {"40ftHC", {12.192, 2.438, 2.896}},
                                                          {"45ftHC", {13.716, 2.438, 2.896}}};
  return types;
}

std::string item(const std::string& list, std::size_t n) {
  return list + "[" + std::to_string(n) + "]";
}

}  // namespace

sim::ExerciseSettings load_exercise(const YamlFile& f, const std::string& folder) {
  sim::ExerciseSettings e;
  const YAML::Node x = f.required(f.root(), "exercise", "");
  e.name = f.text(x, "name", "exercise");
  sim::ScenarioSettings& s = e.scenario;
  s.name = e.name;
  const std::string machine = f.text(x, "machine", "exercise");
  const std::string machine_path = (std::filesystem::path(folder) / machine).lexically_normal().string();
  if (!std::filesystem::exists(machine_path))
    f.fail(x["machine"], "exercise.machine", "no such file: " + machine_path);
  s.crane = load_sts_crane(machine_path);

  const YAML::Node crane = f.required(x, "crane", "exercise");
  s.gantry_y_m = f.number(crane, "gantry_y_m", "exercise.crane", -kHuge, kHuge);
  s.trolley_x_m = f.number(crane, "trolley_x_m", "exercise.crane", s.crane.trolley_drive.min_position_m,
                           s.crane.trolley_drive.max_position_m);
  s.spreader_z_m =
      f.number(crane, "spreader_z_m", "exercise.crane", 0.0, s.crane.trolley_rail_height_m - 2.0, true);

  if (x["blocks"].IsDefined()) {
    const YAML::Node blocks = f.sequence(x, "blocks", "exercise");
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      const std::string at = item("exercise.blocks", n);
      const core::Vec3 half = f.vector3(f.required(blocks[n], "half_extents_m", at), at + ".half_extents_m");
      if (!(half.x > 0 && half.y > 0 && half.z > 0))
        f.fail(blocks[n]["half_extents_m"], at + ".half_extents_m", "must be positive");
      s.blocks.push_back({half, f.vector3(f.required(blocks[n], "position_m", at), at + ".position_m")});
    }
  }

  const YAML::Node containers = f.sequence(x, "containers", "exercise");
  for (std::size_t n = 0; n < containers.size(); ++n) {
    const YAML::Node c = containers[n];
    const std::string at = item("exercise.containers", n);
    sim::ContainerPlacement p;
    p.id = f.text(c, "id", at);
    for (const auto& other : s.containers)
      if (other.id == p.id) f.fail(c["id"], at + ".id", "duplicate container '" + p.id + "'");
    const std::string type = f.text(c, "type", at);
    const auto t = iso_types().find(type);
    if (t == iso_types().end())
      f.fail(c["type"], at + ".type", "unknown container type '" + type + "' (20ft, 40ft, 40ftHC, 45ftHC)");
    p.half_extents_m = t->second * 0.5;
    p.gross_mass_kg =
        f.number(c, "gross_mass_kg", at, 1000.0, 40000.0);  // tare .. above the ISO 30 480 kg max gross
    p.position_m = f.vector3(f.required(c, "position_m", at), at + ".position_m");
    p.yaw_rad = core::deg_to_rad(f.number_or(c, "yaw_deg", at, 0.0, -360.0, 360.0));
    s.containers.push_back(p);
  }

  const YAML::Node moves = f.sequence(x, "moves", "exercise");
  for (std::size_t n = 0; n < moves.size(); ++n) {
    const std::string at = item("exercise.moves", n);
    sim::MoveGoal g;
    g.container_id = f.text(moves[n], "container", at);
    bool known = false;
    for (const auto& c : s.containers)
      known |= c.id == g.container_id;
    if (!known)
      f.fail(moves[n]["container"], at + ".container",
             "no container '" + g.container_id + "' in this exercise");
    g.target_m = f.vector3(f.required(moves[n], "target_m", at), at + ".target_m");
    g.tolerance_m = f.number_or(moves[n], "tolerance_m", at, g.tolerance_m, 0.0, 5.0, true);
    e.moves.push_back(g);
  }
  if (e.moves.empty()) f.fail(moves, "exercise.moves", "an exercise needs at least one move");

  if (x["weather"].IsDefined()) {
    const YAML::Node w = x["weather"];
    const std::string at = "exercise.weather";
    sim::WeatherSettings& ws = s.weather;
    ws.wind_mean_mps = f.number_or(w, "wind_mean_mps", at, ws.wind_mean_mps, 0.0, 80.0);
    ws.wind_from_rad = core::deg_to_rad(f.number_or(w, "wind_from_deg", at, 0.0, 0.0, 360.0));
    ws.turbulence_intensity = f.number_or(w, "turbulence_intensity", at, ws.turbulence_intensity, 0.0, 1.0);
    ws.visibility_m = f.number_or(w, "visibility_m", at, ws.visibility_m, 1.0, 1e5);
    ws.rain_mm_per_h = f.number_or(w, "rain_mm_per_h", at, ws.rain_mm_per_h, 0.0, 500.0);
    ws.time_of_day_h = f.number_or(w, "time_of_day_h", at, ws.time_of_day_h, 0.0, 24.0, false, true);
  }

  if (x["events"].IsDefined()) {
    const YAML::Node events = f.sequence(x, "events", "exercise");
    for (std::size_t n = 0; n < events.size(); ++n) {
      const YAML::Node ev = events[n];
      const std::string at = item("exercise.events", n);
      sim::ScriptedEvent event;
      event.at_s = f.number(ev, "at_s", at, 0.0, 86400.0);
      const std::string kind = f.text(ev, "kind", at);
      if (kind == "gust") {
        event.kind = sim::ScriptedEvent::Kind::kGust;
        event.gust.amplitude_mps = f.number(ev, "amplitude_mps", at, 0.0, 60.0, true);
        event.gust.duration_s = f.number_or(ev, "duration_s", at, 3.0, 0.0, 600.0, true);
      } else if (kind == "hoist_brake_fault") {
        event.kind = sim::ScriptedEvent::Kind::kHoistBrakeFault;
      } else if (kind == "landed_sensor_fault") {
        event.kind = sim::ScriptedEvent::Kind::kLandedSensorFault;
        event.corner = f.integer(ev, "corner", at, 0, 3);
      } else {
        f.fail(ev["kind"], at + ".kind",
               "'" + kind + "' is not gust, hoist_brake_fault or landed_sensor_fault");
      }
      if (!s.events.empty() && event.at_s < s.events.back().at_s)
        f.fail(ev["at_s"], at + ".at_s", "events must be in time order");
      s.events.push_back(event);
    }
  }

  if (x["rules"].IsDefined()) {
    const YAML::Node r = x["rules"];
    sim::EvaluationRules& rules = e.rules;
    rules.time_limit_s =
        f.number_or(r, "time_limit_s", "exercise.rules", rules.time_limit_s, 0.0, 86400.0, true);
    rules.pass_score = f.number_or(r, "pass_score", "exercise.rules", rules.pass_score, 0.0, 100.0);
    rules.hard_landing_mps =
        f.number_or(r, "hard_landing_mps", "exercise.rules", rules.hard_landing_mps, 0.0, 10.0, true);
    rules.sway_limit_m =
        f.number_or(r, "sway_limit_m", "exercise.rules", rules.sway_limit_m, 0.0, 10.0, true);
    rules.collision_speed_mps =
        f.number_or(r, "collision_speed_mps", "exercise.rules", rules.collision_speed_mps, 0.0, 10.0, true);
  }
  return e;
}

sim::ExerciseSettings load_exercise(const std::string& path) {
  return load_exercise(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

}  // namespace harbour::io
