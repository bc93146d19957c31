#include "harbour/io/RouteFiles.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "harbour/core/Text.h"
#include "harbour/io/DataError.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Simulation.h"

namespace harbour::io {
namespace fs = std::filesystem;

std::vector<std::string> stored_metric_names(const sim::ExerciseSettings& exercise) {
  sim::Simulation simulation(exercise.scenario);
  sim::Evaluator evaluator(exercise);
  const scene::Controls neutral;
  simulation.step(neutral);
  evaluator.observe(simulation, neutral);
  std::vector<std::string> names;
  for (const auto& [name, value] : evaluator.metrics().rows())
    names.push_back(name);
  // figures stored once a move is completed (see Metrics::rows)
  if (!exercise.moves.empty()) names.emplace_back("worst_placement_offset_m");
  if (std::any_of(exercise.moves.begin(), exercise.moves.end(),
                  [](const sim::MoveGoal& m) { return m.heading_rad.has_value(); }))
    names.emplace_back("worst_placement_skew_deg");
  // figures stored once a scripted hoist brake fault has come
  const auto brake_fault = [](const sim::ScriptedEvent& e) {
    return e.kind == sim::ScriptedEvent::Kind::kHoistBrakeFault;
  };
  const sim::ScenarioSettings& scenario = exercise.scenario;
  if (std::any_of(scenario.events.begin(), scenario.events.end(), brake_fault) ||
      std::any_of(scenario.lift_events.begin(), scenario.lift_events.end(), brake_fault))
    for (const char* name : {"lifts_under_fault", "stopped_after_fault", "fault_set_down_s"})
      names.emplace_back(name);
  for (const char* skill : {"skill_safety", "skill_precision", "skill_productivity"})
    names.emplace_back(skill);
  return names;
}

std::string stage_exercise_file(const std::string& exercise, const std::string& route_folder,
                                const std::vector<std::string>& exercise_folders) {
  const bool path = exercise.find('/') != std::string::npos ||
                    (exercise.size() > 5 && exercise.substr(exercise.size() - 5) == ".yaml");
  std::error_code ec;
  if (path) {
    const fs::path file = fs::path(route_folder) / exercise;
    return fs::is_regular_file(file, ec) ? file.string() : "";
  }
  for (const std::string& folder : exercise_folders)
    if (const fs::path file = fs::path(folder) / (exercise + ".yaml"); fs::is_regular_file(file, ec))
      return file.string();
  return "";
}

namespace {

std::string known_exercises(const std::vector<std::string>& folders) {
  std::set<std::string> names;
  for (const std::string& folder : folders)
    for (const std::string& n : exercise_names(folder))
      names.insert(n);
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  return list;
}

}  // namespace

training::Route load_route(const YamlFile& f, const std::string& folder,
                           const std::vector<std::string>& exercise_folders) {
  training::Route route;
  route.id = fs::path(f.name()).stem().string();
  const YAML::Node& root = f.root();
  if (!root.IsMap()) f.fail(root, "(file)", "expected a mapping with name, machine and goals");
  route.name = f.text(root, "name", "");
  route.machine = f.text(root, "machine", "");
  const YAML::Node goals = f.sequence(root, "goals", "", 50);
  if (goals.size() == 0) f.fail(goals, "goals", "a route has at least one training goal");
  std::map<std::string, YAML::Node> requires_node;               // per stage, for errors
  std::map<std::string, std::vector<std::string>> metric_names;  // per exercise file
  for (std::size_t g = 0; g < goals.size(); ++g) {
    const std::string at = "goals[" + std::to_string(g) + "]";
    if (!goals[g].IsMap()) f.fail(goals[g], at, "expected a mapping with goal and stages");
    const std::string goal = f.text(goals[g], "goal", at);
    const YAML::Node stages = f.sequence(goals[g], "stages", at, 50);
    if (stages.size() == 0) f.fail(stages, at + ".stages", "a training goal has at least one stage");
    for (std::size_t n = 0; n < stages.size(); ++n) {
      const std::string sat = at + ".stages[" + std::to_string(n) + "]";
      const YAML::Node& node = stages[n];
      if (!node.IsMap()) f.fail(node, sat, "expected a mapping with id and exercise");
      training::Stage stage;
      stage.goal = goal;
      stage.id = f.text(node, "id", sat);
      if (const std::string why = core::why_bad_name(stage.id, 64);
          !why.empty() || stage.id.find(' ') != std::string::npos)
        f.fail(f.required(node, "id", sat), sat + ".id", "a stage id is one word of at most 64 bytes");
      if (route.stage(stage.id))
        f.fail(f.required(node, "id", sat), sat + ".id", "a second stage '" + stage.id + "'");
      stage.exercise = f.text(node, "exercise", sat);
      stage.exercise_file = stage_exercise_file(stage.exercise, folder, exercise_folders);
      if (stage.exercise_file.empty())
        f.fail(f.required(node, "exercise", sat), sat + ".exercise",
               "no exercise '" + stage.exercise + "' (there are: " + known_exercises(exercise_folders) +
                   "; a path is relative to the route's folder)");
      sim::ExerciseSettings exercise;
      try {
        exercise = load_exercise(stage.exercise_file);
      } catch (const std::exception& e) {
        f.fail(f.required(node, "exercise", sat), sat + ".exercise",
               "exercise '" + stage.exercise + "' is bad: " + e.what());
      }
      stage.repetitions =
          f.optional(node, "repetitions", sat) ? f.integer(node, "repetitions", sat, 1, 20) : 1;
      stage.max_attempts =
          f.optional(node, "max_attempts", sat) ? f.integer(node, "max_attempts", sat, 1, 100) : 5;
      if (stage.max_attempts < stage.repetitions)
        f.fail(f.optional(node, "max_attempts", sat).value_or(f.required(node, "repetitions", sat)),
               sat + ".max_attempts",
               "fewer attempts (" + std::to_string(stage.max_attempts) + ") than repetitions (" +
                   std::to_string(stage.repetitions) + ")");
      if (const std::optional<YAML::Node> pass = f.optional_map(node, "pass", sat)) {
        const std::string pat = sat + ".pass";
        if (f.optional(*pass, "score", pat)) stage.min_score = f.number(*pass, "score", pat, 0.0, 100.0);
        if (const std::optional<YAML::Node> metrics = f.optional_map(*pass, "metrics", pat)) {
          std::vector<std::string>& names = metric_names[stage.exercise_file];
          if (names.empty()) names = stored_metric_names(exercise);
          for (const auto& entry : *metrics) {
            const std::string metric = entry.first.Scalar();
            const std::string mat = pat + ".metrics." + metric;
            if (std::find(names.begin(), names.end(), metric) == names.end()) {
              std::string list;
              for (const std::string& m : names)
                list += (list.empty() ? "" : ", ") + m;
              f.fail(entry.first, mat,
                     "exercise '" + stage.exercise + "' stores no figure '" + metric + "' (it stores " +
                         list + ")");
            }
            const YAML::Node limits = f.required_map(*metrics, metric, pat + ".metrics");
            training::MetricBound bound{metric, std::nullopt, std::nullopt};
            if (f.optional(limits, "min", mat)) bound.min = f.number(limits, "min", mat, -1e12, 1e12);
            if (f.optional(limits, "max", mat)) bound.max = f.number(limits, "max", mat, -1e12, 1e12);
            if (!bound.min && !bound.max) f.fail(limits, mat, "give min, max or both");
            if (bound.min && bound.max && *bound.min > *bound.max) f.fail(limits, mat, "min over max");
            stage.bounds.push_back(bound);
          }
        }
      }
      if (f.optional(node, "requires", sat)) {
        const YAML::Node list = f.sequence(node, "requires", sat, 50);
        for (std::size_t k = 0; k < list.size(); ++k) {
          if (!list[k].IsScalar())
            f.fail(list[k], sat + ".requires[" + std::to_string(k) + "]", "a stage id");
          stage.requires_stages.push_back(list[k].Scalar());
        }
        requires_node[stage.id] = list;
      } else if (!route.stages.empty()) {
        stage.requires_stages.push_back(route.stages.back().id);  // by default: the stage before
      }
      route.stages.push_back(stage);
    }
  }
  // prerequisites: stages of this route, without a cycle
  for (std::size_t n = 0; n < route.stages.size(); ++n) {
    const training::Stage& s = route.stages[n];
    for (std::size_t k = 0; k < s.requires_stages.size(); ++k)
      if (!route.stage(s.requires_stages[k]) || s.requires_stages[k] == s.id)
        f.fail(requires_node[s.id][k], "stage '" + s.id + "'.requires[" + std::to_string(k) + "]",
               s.requires_stages[k] == s.id ? "a stage cannot require itself"
                                            : "no stage '" + s.requires_stages[k] + "' in this route");
  }
  std::map<std::string, int> mark;  // 1: on the path, 2: done
  std::vector<std::string> path;
  const std::function<void(const training::Stage&)> visit = [&](const training::Stage& s) {
    mark[s.id] = 1;
    path.push_back(s.id);
    for (std::size_t k = 0; k < s.requires_stages.size(); ++k) {
      const std::string& r = s.requires_stages[k];
      if (mark[r] == 1) {
        std::string cycle;
        for (auto it = std::find(path.begin(), path.end(), r); it != path.end(); ++it)
          cycle += *it + " -> ";
        f.fail(requires_node.count(s.id) ? requires_node[s.id][k] : f.root()["goals"],
               "stage '" + s.id + "'.requires", "a cycle of prerequisites: " + cycle + r);
      }
      if (mark[r] == 0) visit(*route.stage(r));
    }
    path.pop_back();
    mark[s.id] = 2;
  };
  for (const training::Stage& s : route.stages)
    if (mark[s.id] == 0) visit(s);
  f.check_unknown_keys();
  return route;
}

training::Route load_route(const std::string& path, const std::vector<std::string>& exercise_folders) {
  return load_route(YamlFile::load(path), fs::path(path).parent_path().string(), exercise_folders);
}

std::vector<training::Route> load_routes(const std::vector<std::string>& routes_folders,
                                         const std::vector<std::string>& exercise_folders) {
  std::vector<training::Route> routes;
  std::map<std::string, std::string> file_of;  // route name -> its file
  std::set<std::string> seen_folders;
  for (const std::string& folder : routes_folders) {
    std::error_code ec;
    if (!seen_folders.insert(fs::weakly_canonical(folder, ec).string()).second) continue;
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(folder, ec))
      if (entry.path().extension() == ".yaml" && entry.path().filename().string()[0] != '.')
        files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& file : files) {
      const std::string name = fs::path(file).stem().string();
      if (const auto other = file_of.find(name); other != file_of.end())
        throw DataError(other->second, 1, "(file name)",  // the centre's, found first
                        "route '" + name + "' is also " + file +
                            " (the records know a route by its name: give this file another)");
      file_of[name] = file;
      routes.push_back(load_route(file, exercise_folders));
      // people pick a route by its title (progress headings, the start list, the class report): two alike
      // could not be told apart
      for (std::size_t n = 0; n + 1 < routes.size(); ++n)
        if (routes[n].name == routes.back().name)
          throw DataError(file, 1, "route.name",
                          "'" + routes.back().name + "' is also the name of route '" + routes[n].id + "' (" +
                              file_of[routes[n].id] + "): give this route a name of its own");
    }
  }
  return routes;
}

}  // namespace harbour::io
