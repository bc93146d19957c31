// The console API's JSON forms and request parsing.
#include "harbour/console/ConsoleServer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/TeamFiles.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Reports.h"
#include "harbour/sim/MachineType.h"
#include "harbour/training/Figures.h"

namespace harbour::console {

// a stored figure's words, for a page to label it and show it in its unit (shown = stored × scale)
json figure_words_json(const std::string& name) {
  const training::FigureWords w = training::figure_words(name);
  return {{"label", w.label}, {"unit", w.unit}, {"scale", w.scale}, {"about", w.about}};
}

// an attempt's event: when, what (the stored kind and value) and in words
json attempt_event_json(double at_s, const std::string& kind, double value) {
  return {{"at_s", at_s}, {"kind", kind}, {"value", value}, {"text", training::event_text(kind, value)}};
}

// how deep `text` nests arrays and objects (outside strings): refused before parsing when too deep
int json_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{')
      deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}')
      --depth;
  }
  return deepest;
}

// a query parameter's value, percent-decoded ('+' a space); "" when absent or not decodable
std::string query_param(const std::string& query, const std::string& key) {
  std::size_t start = 0;
  while (start <= query.size()) {
    const std::size_t end = std::min(query.find('&', start), query.size());
    const std::string pair = query.substr(start, end - start);
    if (pair.rfind(key + "=", 0) == 0) {
      std::string value;
      for (std::size_t i = key.size() + 1; i < pair.size(); ++i) {
        if (pair[i] == '+') {
          value += ' ';
        } else if (pair[i] == '%') {
          if (i + 2 >= pair.size() || !std::isxdigit(static_cast<unsigned char>(pair[i + 1])) ||
              !std::isxdigit(static_cast<unsigned char>(pair[i + 2])))
            return "";
          value += static_cast<char>(std::stoi(pair.substr(i + 1, 2), nullptr, 16));
          i += 2;
        } else {
          value += pair[i];
        }
      }
      return value;
    }
    start = end + 1;
  }
  return "";
}

// a JSON object from a request or message body, or why not: too deep, not JSON, not an object, or an object
// that gives a key twice (parsers disagree on which one counts: the last here, the first elsewhere)
std::optional<json> parse_object(const std::string& text, std::string& why) {
  if (json_depth(text) > kMaxJsonDepth) {
    why = "JSON nested too deep";
    return std::nullopt;
  }
  std::vector<std::set<std::string>> keys;  // of each object open at this point
  std::string duplicate;
  const json::parser_callback_t watch = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) {
      keys.emplace_back();
    } else if (event == json::parse_event_t::object_end) {
      if (!keys.empty()) keys.pop_back();
    } else if (event == json::parse_event_t::key && !keys.empty() && parsed.is_string() &&
               !keys.back().insert(parsed.get<std::string>()).second && duplicate.empty()) {
      duplicate = parsed.get<std::string>();
    }
    return true;
  };
  json value = json::parse(text, watch, false);
  if (value.is_discarded() || !value.is_object()) {
    why = "the body is not a JSON object";
    return std::nullopt;
  }
  if (!duplicate.empty()) {
    why = "key '" + core::printable(duplicate, 64) + "' is given twice";
    return std::nullopt;
  }
  return value;
}

// a string field of at most `longest` bytes with no control or bidirectional formatting characters (a
// password: no control characters); "" and a reason when missing or bad
std::optional<std::string> text_field(const json& body, const char* field, std::size_t longest,
                                      std::string& why, bool required, bool password) {
  const auto found = body.find(field);
  if (found == body.end() || found->is_null()) {
    if (required) why = std::string("field '") + field + "' is missing";
    return required ? std::nullopt : std::optional<std::string>("");
  }
  if (!found->is_string()) {
    why = std::string("field '") + field + "' is not a string";
    return std::nullopt;
  }
  const std::string value = found->get<std::string>();
  if (value.size() > longest) {
    why = std::string("field '") + field + "' is longer than " + std::to_string(longest) + " bytes";
    return std::nullopt;
  }
  if (password) {
    for (const unsigned char c : value)
      if (c < 0x20 || c == 0x7f) {
        why = std::string("field '") + field + "' holds control characters";
        return std::nullopt;
      }
  } else if (const std::string bad = core::why_bad_name(value, longest); !value.empty() && !bad.empty()) {
    why = std::string("field '") + field + "' " + bad;
    return std::nullopt;
  }
  return value;
}

// JSON text; strings that are not UTF-8 (a foreign DDS peer's, a database's) are repaired, not thrown on
std::string dump(const json& value) {
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string content_type(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

// The shipped team sessions (data/teams) and their roles; a team file in error is listed with its error.
json team_list(const std::vector<std::string>& exercise_folders) {
  json list = json::array();
  std::set<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& f : std::filesystem::directory_iterator(records::shipped_data_folder() + "/teams", ec))
    if (f.path().extension() == ".yaml") files.insert(f.path());
  for (const std::filesystem::path& file : files) {
    try {
      const io::Team team = io::load_team(file.string(), exercise_folders);
      json roles = json::array();
      for (const io::TeamRole& r : team.roles)
        roles.push_back(
            {{"role", r.role}, {"exercise", std::filesystem::path(r.exercise_file).stem().string()}});
      list.push_back({{"name", team.name}, {"roles", roles}});
    } catch (const std::exception& e) {
      list.push_back({{"name", file.stem().string()}, {"error", e.what()}});
    }
  }
  return list;
}

json status_json(const std::string& name, const net::ConsoleLink::Station& s) {
  const net::StationStatus& st = s.status;
  return {{"station", name},
          {"host", st.host().to_string()},
          {"state", s.gone   ? "offline"
                    : s.lost ? "lost"
                             : st.state().to_string()},
          {"machine", st.machine().to_string()},
          {"exercise", st.exercise().to_string()},
          {"trainee", st.trainee().to_string()},
          {"attempt", st.attempt()},
          {"time_s", st.time_s()},
          {"time_limit_s", st.time_limit_s()},
          {"real_time_factor", st.real_time_factor()},
          {"late_ticks", st.late_ticks()},
          {"skipped_ticks", st.skipped_ticks()},
          {"keeping_real_time", st.keeping_real_time()},
          {"devices_missing", st.devices_missing()},
          {"physics_warnings", st.physics_warnings()},
          {"diverged", st.diverged()},
          {"score", st.score()},
          {"moves_done", st.moves_done()},
          {"moves_total", st.moves_total()},
          {"collisions", st.collisions()},
          {"message", st.message().to_string()},
          {"team", st.team().to_string()},
          {"role", st.role().to_string()},
          {"states_received", s.state_count}};
}

json event_json(const net::StationEvent& e) {
  return {{"type", "event"},
          {"station", e.station().to_string()},
          {"attempt", e.attempt()},
          {"time_s", e.time_s()},
          {"kind", e.kind().to_string()},
          {"value", e.value()},
          {"text", e.text().to_string()},
          {"words", training::event_text(e.kind().to_string(), e.value(), e.text().to_string())}};
}

// a figure for the 3D view, to `unit` (a millimetre, a quaternion's 1e-5): the JSON stays short
double rounded(float value, double per_unit) {
  return std::round(static_cast<double>(value) * per_unit) / per_unit;
}

json vec3_json(const core::Vec3& v) {
  return {v.x, v.y, v.z};
}

// A station's (or a replay's) state for a browser: indicators by name; with `view`, the entities' poses (x,
// y, z, qx, qy, qz, qw each, in the scene's order) and the ropes' polylines.
json state_json(const std::string& station, const net::StationState& st, const net::StationScene* scene,
                bool view) {
  json indicators = json::object();
  if (scene)
    for (std::size_t n = 0; n < st.indicators().size() && n < scene->indicator_names().size(); ++n)
      indicators[scene->indicator_names()[n].to_string()] = st.indicators()[n];
  json state{{"type", "state"},
             {"station", station},
             {"attempt", st.attempt()},
             {"time_s", st.time_s()},
             {"held", st.held()},
             {"wind_mps", {st.wind_mps()[0], st.wind_mps()[1], st.wind_mps()[2]}},
             {"time_of_day_h", st.time_of_day_h()},
             {"visibility_m", st.visibility_m()},
             {"rain_mm_per_h", st.rain_mm_per_h()},
             {"cloud_oktas", st.cloud_oktas()},
             {"indicators", indicators}};
  if (!view) return state;
  json poses = json::array();
  for (std::size_t n = 0; n < st.entity_poses().size(); ++n)
    poses.push_back(rounded(st.entity_poses()[n], n % 7 < 3 ? 1e3 : 1e5));
  json points = json::array();
  for (const float v : st.rope_points_m())
    points.push_back(rounded(v, 1e3));
  state["water_level_m"] = st.water_level_m();
  state["poses"] = std::move(poses);
  state["ropes"] = {{"counts", st.rope_point_counts()}, {"points", std::move(points)}};
  return state;
}

// A station's (or a replay's, or a design's) bulk material for the 3D view: each grid's samples, spacing,
// pose (its corner) and heights above its floor [cm resolution].
json bulk_json(const std::string& station, const net::StationBulk& bulk) {
  json grids = json::array();
  std::size_t first = 0;
  for (std::size_t g = 0; g < bulk.samples_x().size() && g < bulk.samples_y().size() &&
                          g < bulk.sample_m().size() && 7 * g + 7 <= bulk.grid_poses().size();
       ++g) {
    const std::size_t count = std::size_t{bulk.samples_x()[g]} * bulk.samples_y()[g];
    if (first + count > bulk.heights_m().size()) break;  // a damaged sample: what is whole
    json heights = json::array();
    for (std::size_t k = first; k < first + count; ++k)
      heights.push_back(rounded(bulk.heights_m()[k], 1e2));
    first += count;
    json pose = json::array();
    for (std::size_t k = 7 * g; k < 7 * g + 7; ++k)
      pose.push_back(rounded(bulk.grid_poses()[k], 1e4));
    grids.push_back({{"nx", bulk.samples_x()[g]},
                     {"ny", bulk.samples_y()[g]},
                     {"step_m", bulk.sample_m()[g]},
                     {"pose", std::move(pose)},
                     {"heights", std::move(heights)}});
  }
  return {{"type", "bulk"},
          {"station", station},
          {"attempt", bulk.attempt()},
          {"time_s", bulk.time_s()},
          {"grids", std::move(grids)}};
}

// What a station's 3D view draws: its entities' names, looks and half sizes, once per attempt.
json scene_json(const std::string& station, const net::StationScene& scene) {
  json entities = json::array();
  const auto& extents = scene.entity_half_extents_m();
  for (std::size_t n = 0; n < scene.entity_names().size() && n < scene.entity_visuals().size(); ++n)
    entities.push_back(
        {{"name", scene.entity_names()[n].to_string()},
         {"visual", scene.entity_visuals()[n].to_string()},
         {"livery_key", scene::livery_key(scene.entity_names()[n].to_string())},
         {"half_m", 3 * n + 2 < extents.size() ? json{extents[3 * n], extents[3 * n + 1], extents[3 * n + 2]}
                                               : json{0.5, 0.5, 0.5}}});
  return {{"type", "scene"},
          {"station", station},
          {"attempt", scene.attempt()},
          {"machine", scene.machine().to_string()},
          {"entities", std::move(entities)}};
}

// The looks (data/visuals/*.yaml) as the browser's 3D view reads them; a deckhouse as its parts (its block,
// windows, wheelhouse, wings and mast); a container, tyre, shell, hull, mesh, girder, walkway, stairs,
// cylinder or spreader part is drawn as the box it fills, a member as its box turned `along` it.
json looks_json(const ig::Looks& looks) {
  json visuals = json::object();
  for (const auto& [key, visual] : looks.visuals) {
    json parts = json::array();
    std::vector<ig::VisualPart> drawn;
    for (const ig::VisualPart& part : visual.parts) {
      const std::vector<ig::VisualPart> pieces = part.shape == ig::VisualPart::Shape::kDeckhouse
                                                     ? ig::drawn_parts(part, *part.size_m)
                                                     : std::vector<ig::VisualPart>{part};
      drawn.insert(drawn.end(), pieces.begin(), pieces.end());
    }
    for (const ig::VisualPart& part : drawn) {
      // a walkway as its deck, a flight as the slab along its pitch (turned by its yaw), a member along
      // itself
      std::optional<core::Vec3> size = part.size_m;
      core::Vec3 at = part.centre_m, along = part.along;
      if (size && part.shape == ig::VisualPart::Shape::kWalkway) {
        at.z -= size->z / 2.0;
        size->z = 0.05;
      } else if (size && part.shape == ig::VisualPart::Shape::kStairs) {
        const core::Vec3 rise{size->x * std::cos(part.yaw_rad), size->x * std::sin(part.yaw_rad), size->z};
        along = rise * (1.0 / core::length(rise));
        size = core::Vec3{core::length(rise), size->y, 0.3};
      }
      static constexpr const char* kShapes[] = {"box",      "lattice", "container", "tyre",     "shell",
                                                "hull",     "mesh",    "girder",    "walkway",  "stairs",
                                                "cylinder", "member",  "spreader",  "deckhouse"};
      static_assert(std::size(kShapes) == static_cast<std::size_t>(ig::VisualPart::Shape::kDeckhouse) + 1);
      parts.push_back({{"shape", kShapes[static_cast<int>(part.shape)]},
                       {"size_m", size ? vec3_json(*size) : json(nullptr)},
                       {"at_m", vec3_json(at)},
                       {"color", vec3_json(part.color)},
                       {"livery", part.livery},
                       {"bay_m", part.bay_m},
                       {"member_m", part.member_m},
                       {"along", vec3_json(along)}});
    }
    json liveries = json::array();
    for (const core::Vec3& c : visual.liveries)
      liveries.push_back(vec3_json(c));
    visuals[key] = {{"parts", std::move(parts)}, {"liveries", std::move(liveries)}};
  }
  json scenery = json::array();
  for (const ig::SceneryPart& part : looks.scenery)
    scenery.push_back({{"shape", part.shape == ig::SceneryPart::Shape::kBox ? "box" : "cylinder"},
                       {"at_m", vec3_json(part.centre_m)},
                       {"size_m", vec3_json(part.size_m)},
                       {"color", vec3_json(part.color)},
                       {"repeat", part.repeat},
                       {"step_m", vec3_json(part.step_m)}});
  // the trainee's HUD lines: the console's live line shows the station's indicators as the cab shows them
  json hud = json::array();
  for (const ig::HudItem& h : looks.hud)
    hud.push_back({{"indicator", h.indicator},
                   {"label", h.label},
                   {"unit", h.unit},
                   {"decimals", h.decimals},
                   {"lamp", h.lamp},
                   {"scale", h.scale},
                   {"words", h.words},
                   {"words_from", h.words_from},
                   {"shown_while", h.shown_while},
                   {"machines", h.machines},
                   {"except", h.except}});
  // the machines' hydraulic jacks between two of their entities (by look), redrawn as those move
  json jacks = json::array();
  for (const ig::Jack& j : looks.jacks)
    jacks.push_back({{"from", j.from_entity},
                     {"to", j.to_entity},
                     {"from_m", vec3_json(j.from_m)},
                     {"to_m", vec3_json(j.to_m)},
                     {"barrel_m", j.barrel_m},
                     {"rod_m", j.rod_m},
                     {"diameter_m", j.diameter_m},
                     {"color", vec3_json(j.color)}});
  return {{"visuals", std::move(visuals)},
          {"scenery", std::move(scenery)},
          {"hud", std::move(hud)},
          {"jacks", std::move(jacks)}};
}

json route_json(const training::Route& r) {
  json stages = json::array();
  for (const training::Stage& s : r.stages) {
    json bounds = json::array();
    for (const training::MetricBound& b : s.bounds)
      bounds.push_back({{"metric", b.metric},
                        {"min", b.min ? json(*b.min) : json(nullptr)},
                        {"max", b.max ? json(*b.max) : json(nullptr)}});
    stages.push_back({{"id", s.id},
                      {"goal", s.goal},
                      {"exercise", s.exercise},
                      {"min_score", s.min_score ? json(*s.min_score) : json(nullptr)},
                      {"bounds", bounds},
                      {"repetitions", s.repetitions},
                      {"max_attempts", s.max_attempts},
                      {"requires", s.requires_stages}});
  }
  return {{"id", r.id}, {"name", r.name}, {"machine", r.machine}, {"stages", stages}};
}

// What the designer shows of a checked design: its summary, its forms, and its world at the first instant
// drawn by the same 3D view as a station's. Builds the world (throws what building it throws).
json design_preview(const std::string& folder, const DesignCheck& design) {
  const sim::Simulation simulation(design.exercise.scenario);
  auto snapshot = std::make_unique<scene::Snapshot>();
  simulation.write_snapshot(*snapshot);
  const net::StationScene published = net::scene_message(simulation.scene(), 0);
  json bulk;
  if (const bulk::BulkWorld* material = simulation.bulk()) {
    scene::BulkView view;
    bulk::publish(*material, view);
    bulk = bulk_json("designer", net::bulk_message(view, 0, 0.0));
  }
  const sim::ExerciseSettings& x = design.exercise;
  return {
      {"exercise", x.name},
      {"machine", x.scenario.machine.kind()},
      {"version", design.version},
      {"containers", x.scenario.containers.size()},
      {"moves", x.moves.size()},
      {"events", x.scenario.events.size() + x.scenario.lift_events.size()},
      {"time_limit_s", x.rules.time_limit_s},
      {"pass_score", x.rules.pass_score},
      {"wind_mps", x.scenario.weather.wind_mean_mps},
      {"form", design_form(folder, design)},
      {"scene", scene_json("designer", published)},
      {"state", state_json("designer", net::state_message(*snapshot, simulation.scene().entities.size(), 0),
                           &published, true)},
      {"bulk", bulk}};
}

}  // namespace harbour::console
