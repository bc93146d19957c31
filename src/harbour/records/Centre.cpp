#include "harbour/records/Centre.h"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>

namespace harbour::records {
namespace {

std::vector<std::string> with_shipped(const std::string& own, const std::string& shipped) {
  if (own.empty()) return {shipped};
  return {own, shipped};
}

}  // namespace

std::string shipped_data_folder() {
  return HARBOUR_DATA_DIR;
}

std::vector<std::string> CentreFolders::exercise_folders() const {
  return with_shipped(exercises, shipped_data_folder() + "/exercises");
}

std::vector<std::string> CentreFolders::route_folders() const {
  return with_shipped(routes, shipped_data_folder() + "/routes");
}

std::string default_database() {
  const char* xdg = std::getenv("XDG_DATA_HOME");
  const char* home = std::getenv("HOME");
  const std::filesystem::path base = xdg && *xdg
                                         ? std::filesystem::path(xdg)
                                         : std::filesystem::path(home && *home ? home : ".") / ".local/share";
  std::filesystem::create_directories(base / "harboursim");
  return "sqlite3://db=" + (base / "harboursim" / "records.db").string();
}

std::string resolve_exercise(const std::string& name_or_path, const std::string& centre,
                             const std::string& version) {
  namespace fs = std::filesystem;
  if (fs::is_regular_file(name_or_path)) return name_or_path;
  const fs::path shipped_folder = fs::path(shipped_data_folder()) / "exercises";
  std::vector<fs::path> folders;
  if (!centre.empty()) folders.push_back(centre);
  folders.push_back(shipped_folder);
  if (!centre.empty() && fs::is_regular_file(fs::path(centre) / (name_or_path + ".yaml")) &&
      fs::is_regular_file(shipped_folder / (name_or_path + ".yaml")) &&
      !fs::equivalent(fs::path(centre), shipped_folder))
    throw std::runtime_error(
        "exercise '" + name_or_path + "' is both the centre's (" +
        (fs::path(centre) / (name_or_path + ".yaml")).string() +
        ") and a shipped one: a centre's exercise takes a name of its own (rename the file "
        "and its exercise.name)");
  for (const fs::path& folder : folders) {
    const fs::path file = folder / (name_or_path + ".yaml");
    if (!fs::is_regular_file(file)) continue;
    // an earlier version the designer kept, when the exercise has changed since
    const fs::path kept = folder / "versions" / (name_or_path + "-" + version + ".yaml");
    if (!version.empty() && io::exercise_version(file.string()) != version && fs::is_regular_file(kept))
      return kept.string();
    return file.string();
  }
  std::string list;
  for (const fs::path& folder : folders)
    for (const std::string& n : io::exercise_names(folder.string()))
      list += (list.empty() ? "" : ", ") + n;
  throw std::runtime_error("no exercise file '" + name_or_path + "' and no exercise of that name (" + list +
                           ")");
}

sim::ExerciseSettings load_resolved_exercise(const std::string& file) {
  return io::load_exercise_source(io::read_exercise_source(file));
}

io::ExerciseSource attempt_exercise(RecordsStore& db, const AttemptRow& attempt,
                                    const std::string& centre_exercises, std::string& inexact) {
  namespace fs = std::filesystem;
  inexact.clear();
  if (!attempt.exercise_version.empty())
    if (std::optional<io::ExerciseSource> kept = db.kept_exercise(attempt.exercise_version)) {
      // its paths resolve where they did; on another PC, from where an exercise of its name stands here
      if (!fs::is_directory(kept->folder)) {
        try {
          kept->folder =
              io::read_exercise_source(resolve_exercise(attempt.exercise, centre_exercises)).folder;
        } catch (const std::exception&) {
          kept->folder = shipped_data_folder() + "/exercises";
        }
      }
      return *kept;
    }
  io::ExerciseSource source = io::read_exercise_source(
      resolve_exercise(attempt.exercise, centre_exercises, attempt.exercise_version));
  if (!attempt.exercise_version.empty() && source.version != attempt.exercise_version)
    inexact = "exercise " + attempt.exercise + " has changed since attempt " + std::to_string(attempt.id) +
              " (version " + attempt.exercise_version + ", now " + source.version +
              ") and neither the records nor the designer keep the version it ran: this replay runs on the "
              "current file and may not show what the trainee had";
  return source;
}

}  // namespace harbour::records
