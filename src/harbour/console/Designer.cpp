#include "harbour/console/Designer.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/core/Units.h"
#include "harbour/io/BulkFiles.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/VesselFiles.h"
#include "harbour/sim/MachineType.h"
#include "harbour/sim/Simulation.h"
#include "harbour/sim/Vessel.h"

namespace harbour::console {

namespace {

namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// written beside and renamed over: a reader never sees half a file
void replace_file(const fs::path& path, const std::string& text) {
  const fs::path partial = path.string() + ".partial";
  write_file(partial, text);
  fs::rename(partial, path);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// a saved exercise's name: a file name and a name the console's lists and the stations take
std::string why_bad_design_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return "1 to 64 characters";
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
      return "lower-case letters, digits, _ and - only";
  return "";
}

}  // namespace

bool designed(const std::string& text) {
  return text.find(std::string("\n") + kDesignedMarker + "\n") != std::string::npos ||
         text.rfind(std::string(kDesignedMarker) + "\n", 0) == 0;
}

namespace {

// the marker last, so that the loader's line numbers are the designer's
std::string with_marker(const std::string& yaml) {
  return designed(yaml) ? yaml
                        : yaml + (yaml.empty() || yaml.back() == '\n' ? "" : "\n") + kDesignedMarker + "\n";
}

}  // namespace

DesignCheck check_design(const std::string& folder, const std::string& yaml) {
  if (!fs::is_directory(folder))
    throw std::runtime_error("the exercise folder " + folder + " does not exist");
  DesignCheck check;
  check.text = with_marker(yaml);
  // a file of its own in the folder (so relative paths resolve as they will), named in the errors as the
  // design
  const fs::path probe =
      fs::path(folder) / (".design-" + std::to_string(::getpid()) + "-" +
                          std::to_string(reinterpret_cast<std::uintptr_t>(&check)) + ".yaml");
  write_file(probe, check.text);
  struct Remove {
    fs::path path;
    ~Remove() {
      std::error_code ignored;
      fs::remove(path, ignored);
    }
  } remove{probe};
  try {
    check.exercise = io::load_exercise(probe.string());
  } catch (const std::exception& e) {
    std::string why = e.what();
    for (std::size_t at; (at = why.find(probe.string())) != std::string::npos;)
      why.replace(at, probe.string().size(), "the design");
    throw std::invalid_argument(why);
  }
  if (const std::string why = why_bad_design_name(check.exercise.name); !why.empty())
    throw std::invalid_argument("the design: field 'exercise.name' '" + core::printable(check.exercise.name) +
                                "': the file's name, " + why);
  if (check.exercise.about) {
    // people pick exercises by title: the centre's and the shipped ones each have their own
    const std::string why = io::why_title_taken({folder, records::shipped_data_folder() + "/exercises"},
                                                check.exercise.about->title, check.exercise.name);
    if (!why.empty()) throw std::invalid_argument("the design: field 'exercise.about.title' " + why);
  }
  check.version = io::exercise_version(probe.string());
  return check;
}

std::string save_design(const std::string& folder, const DesignCheck& design) {
  const fs::path file = fs::path(folder) / (design.exercise.name + ".yaml");
  // a centre's exercise named as a shipped one would stand in for it at every station and route
  const fs::path shipped =
      fs::path(records::shipped_data_folder()) / "exercises" / (design.exercise.name + ".yaml");
  std::error_code ec;
  if (fs::is_regular_file(shipped) && !fs::equivalent(file, shipped, ec))
    throw std::logic_error(
        "exercise '" + design.exercise.name +
        "' is a shipped exercise: save the design under a name of its own (exercise.name)");
  if (fs::exists(file) && !designed(read_file(file)))
    throw std::logic_error("exercise '" + design.exercise.name +
                           "' was not made by the designer (a shipped one?): save the design under another "
                           "exercise.name");
  const fs::path versions = fs::path(folder) / "versions";
  fs::create_directories(versions);
  write_file(versions / (design.exercise.name + "-" + design.version + ".yaml"), design.text);
  replace_file(file, design.text);
  return file.string();
}

nlohmann::json design_form(const std::string& folder, const DesignCheck& design) {
  using json = nlohmann::json;
  const sim::ScenarioSettings& s = design.exercise.scenario;
  const std::string machine = s.machine.kind();
  json form = {{"machine", machine}};
  if (s.vessel) {
    const sim::VesselSettings& v = s.vessel->vessel;
    const sim::VesselGeometry geometry(*s.vessel);
    json rows = json::array(), bays = json::array(), hold = json::array(), deck = json::array(),
         holds = json::array();
    std::vector<std::pair<double, int>> by_x;  // port (-x) to starboard
    for (int row = 0; row <= v.rows + 1; ++row)
      if (const auto x = geometry.row_x(row)) by_x.emplace_back(*x, row);
    std::sort(by_x.begin(), by_x.end());
    for (const auto& [x, row] : by_x)
      rows.push_back(row);
    for (const sim::VesselSettings::Bay& bay : v.bays)
      bays.push_back(bay.number);
    for (int tier = 2; tier <= 2 * v.hold_tiers; tier += 2)
      hold.push_back(tier);
    for (int tier = 82; tier < 82 + 2 * v.deck_tiers; tier += 2)
      deck.push_back(tier);
    for (const sim::VesselSettings::Hold& h : v.holds)
      holds.push_back(h.number);
    form["vessel"] = {{"name", v.name},     {"kind", v.kind == sim::VesselKind::kBulk ? "bulk" : "container"},
                      {"bays", bays},       {"rows", rows},
                      {"hold_tiers", hold}, {"deck_tiers", deck},
                      {"holds", holds}};
  }
  if (s.yard_block)
    form["yard_block"] = {
        {"bays", 2 * s.yard_block->bays - 1}, {"rows", s.yard_block->rows}, {"tiers", s.yard_block->tiers}};
  const io::StartPoseForm pose = io::start_pose_form(s.machine);
  json pose_fields = json::array();
  for (const io::StartPoseField& p : pose.fields)
    pose_fields.push_back({{"key", p.key},
                           {"component", p.component},
                           {"min", p.min},
                           {"max", p.max},
                           {"optional", p.optional},
                           {"fallback", p.fallback}});
  form["start_pose"] = {{"section", pose.section}, {"fields", pose_fields}};
  const io::HarmonicRange& sea = io::kHarmonicRange;
  form["sea_harmonic"] = {{"max_amplitude_m", sea.max_heave_m},
                          {"max_amplitude_deg", sea.max_angle_deg},
                          {"min_period_s", sea.min_period_s},
                          {"max_period_s", sea.max_period_s}};
  const sim::MachineType& type = s.machine.type();
  // the deductions only where the machine can incur them (a jack-knife is no STS's)
  const auto figures = [&](const std::vector<io::RuleField>& fields, bool deductions) {
    json list = json::array();
    for (const io::RuleField& f : fields)
      if (!deductions || type.can_incur(f.key))
        list.push_back(
            {{"key", f.key}, {"value", design.exercise.rules.*f.value}, {"min", f.min}, {"max", f.max}});
    return list;
  };
  form["rules"] = {{"thresholds", figures(io::rule_thresholds(), false)},
                   {"deductions", figures(io::rule_deductions(), true)}};
  const sim::WeatherSettings& w = s.weather;
  form["weather"] = {{"wind_mean_mps", w.wind_mean_mps},
                     {"wind_from_deg", core::rad_to_deg(w.wind_from_rad)},
                     {"turbulence_intensity", w.turbulence_intensity},
                     {"visibility_m", w.visibility_m},
                     {"rain_mm_per_h", w.rain_mm_per_h},
                     {"cloud_oktas", w.cloud_oktas},
                     {"time_of_day_h", w.time_of_day_h}};
  form["event_kinds"] = io::event_kinds(type);
  form["serves_trucks"] = type.serves_trucks;
  json vessels = json::array(), materials = json::array();
  const fs::path vessel_folder = fs::path(folder) / ".." / "vessels";
  std::error_code ec;
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(vessel_folder, ec))
    if (entry.path().extension() == ".yaml")
      files.push_back("../vessels/" + entry.path().filename().string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files)
    vessels.push_back(f);
  if (s.bulk) {
    try {
      for (const bulk::Material& m :
           io::load_materials((fs::path(folder) / ".." / "materials.yaml").string()))
        materials.push_back(m.name);
    } catch (const std::exception&) {
      materials.push_back(s.bulk->material.name);  // the design's own materials file names it
    }
  }
  form["catalogue"] = {{"vessels", vessels}, {"materials", materials}};
  return form;
}

std::string design_source(const std::string& folder, const std::string& name) {
  if (!why_bad_design_name(name).empty())
    throw std::out_of_range("no exercise '" + core::printable(name) + "'");
  const fs::path file = fs::path(folder) / (name + ".yaml");
  if (!fs::is_regular_file(file)) throw std::out_of_range("no exercise '" + name + "'");
  return read_file(file);
}

RouteCheck check_route_text(const records::CentreFolders& centre, const std::string& id,
                            const std::string& yaml) {
  if (const std::string why = why_bad_design_name(id); !why.empty())
    throw std::invalid_argument("the route's file name '" + core::printable(id, 64) + "': " + why);
  RouteCheck check;
  check.text = with_marker(yaml);
  const std::string folder = centre.route_folders().front();
  try {
    // read as the file it will be, so its relative paths and its name are what the stations will see
    check.route =
        io::load_route(io::YamlFile::parse(check.text, id + ".yaml"), folder, centre.exercise_folders());
  } catch (const std::exception& e) {
    throw std::invalid_argument(e.what());
  }
  return check;
}

std::string save_route(const records::CentreFolders& centre, const RouteCheck& route) {
  const std::vector<std::string> folders = centre.route_folders();
  const fs::path file = fs::path(folders.front()) / (route.route.id + ".yaml");
  std::error_code ec;
  for (std::size_t n = 1; n < folders.size(); ++n)
    if (!fs::equivalent(folders[n], folders.front(), ec) &&
        fs::is_regular_file(fs::path(folders[n]) / (route.route.id + ".yaml")))
      throw std::logic_error("route '" + route.route.id +
                             "' is a shipped route: save yours under another name");
  if (fs::exists(file) && !designed(read_file(file)))
    throw std::logic_error(
        "route '" + route.route.id +
        "' was not written in the route editor (a shipped one?): save yours under another name");
  fs::create_directories(folders.front());
  replace_file(file, route.text);
  return file.string();
}

std::string route_source(const records::CentreFolders& centre, const std::string& id) {
  if (!why_bad_design_name(id).empty()) throw std::out_of_range("no route '" + core::printable(id) + "'");
  for (const std::string& folder : centre.route_folders())
    if (const fs::path file = fs::path(folder) / (id + ".yaml"); fs::is_regular_file(file))
      return read_file(file);
  throw std::out_of_range("no route '" + id + "'");
}

}  // namespace harbour::console
