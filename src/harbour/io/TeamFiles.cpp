#include "harbour/io/TeamFiles.h"

#include <algorithm>

#include <filesystem>

#include "harbour/io/RouteFiles.h"

namespace harbour::io {

namespace fs = std::filesystem;

namespace {
// why `name` cannot name a team or a role on the network ("" when it can)
std::string why_bad_name(const std::string& name, std::size_t most, bool dots) {
  if (name.empty() || name.size() > most) return "1 to " + std::to_string(most) + " characters";
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
          c == '_' || (dots && c == '.')))
      return dots ? "letters, digits, '-', '_' and '.' only" : "letters, digits, '-' and '_' only";
  return "";
}
}  // namespace

const TeamRole* Team::find(const std::string& role) const {
  for (const TeamRole& r : roles)
    if (r.role == role) return &r;
  return nullptr;
}

std::string Team::role_list() const {
  std::string list;
  for (const TeamRole& r : roles)
    list += (list.empty() ? "" : ", ") + r.role;
  return list;
}

Team load_team(const YamlFile& f, const std::string& folder,
               const std::vector<std::string>& exercise_folders) {
  const YAML::Node team = f.required_map(f.root(), "team", "");
  Team t;
  t.name = f.text(team, "name", "team");
  if (const std::string why = why_bad_name(t.name, 64, true); !why.empty())
    f.fail(team["name"], "team.name", "'" + t.name + "': " + why);
  const YAML::Node roles = f.sequence(team, "roles", "team", 8);
  if (roles.size() < 2) f.fail(roles, "team.roles", "a team has 2 to 8 roles");
  for (std::size_t k = 0; k < roles.size(); ++k) {
    const std::string path = "team.roles[" + std::to_string(k) + "]";
    TeamRole r;
    r.role = f.text(roles[k], "role", path);
    if (const std::string why = why_bad_name(r.role, 32, false); !why.empty())
      f.fail(roles[k]["role"], path + ".role", "'" + r.role + "': " + why);
    if (t.find(r.role)) f.fail(roles[k]["role"], path + ".role", "'" + r.role + "' is named twice");
    const std::string exercise = f.text(roles[k], "exercise", path);
    r.exercise_file = stage_exercise_file(exercise, folder, exercise_folders);
    if (r.exercise_file.empty())
      f.fail(roles[k]["exercise"], path + ".exercise", "no exercise '" + exercise + "'");
    if (f.optional(roles[k], "trucks", path)) {
      const YAML::Node trucks = f.sequence(roles[k], "trucks", path, 8);
      for (std::size_t n = 0; n < trucks.size(); ++n) {
        const std::string at = path + ".trucks[" + std::to_string(n) + "]";
        if (!trucks[n].IsScalar()) f.fail(trucks[n], at, "is a role's name");
        r.trucks.push_back(trucks[n].as<std::string>());
        if (const std::string why = why_bad_name(r.trucks.back(), 32, false); !why.empty())
          f.fail(trucks[n], at, "'" + r.trucks.back() + "': " + why);
      }
    }
    t.roles.push_back(r);
  }
  // each truck another role, serving one crane once
  std::vector<std::string> serving;
  for (std::size_t k = 0; k < roles.size(); ++k)
    for (std::size_t n = 0; n < t.roles[k].trucks.size(); ++n) {
      const std::string& truck = t.roles[k].trucks[n];
      const YAML::Node at = roles[k]["trucks"][n];
      const std::string path = "team.roles[" + std::to_string(k) + "].trucks[" + std::to_string(n) + "]";
      if (!t.find(truck) || truck == t.roles[k].role)
        f.fail(at, path, "'" + truck + "' is not another role of this team (" + t.role_list() + ")");
      if (std::find(serving.begin(), serving.end(), truck) != serving.end())
        f.fail(at, path, "'" + truck + "' already serves as a truck");
      serving.push_back(truck);
    }
  f.check_unknown_keys();
  return t;
}

Team load_team(const std::string& path, const std::vector<std::string>& exercise_folders) {
  return load_team(YamlFile::load(path), fs::path(path).parent_path().string(), exercise_folders);
}

}  // namespace harbour::io
