#include "Designer.h"

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/io/ExerciseFiles.h"

namespace harbour::apps {

namespace {

namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
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

DesignCheck check_design(const std::string& folder, const std::string& yaml) {
  if (!fs::is_directory(folder))
    throw std::runtime_error("the exercise folder " + folder + " does not exist");
  DesignCheck check;
  // the marker last, so that the loader's line numbers are the designer's
  check.text = designed(yaml)
                   ? yaml
                   : yaml + (yaml.empty() || yaml.back() == '\n' ? "" : "\n") + kDesignedMarker + "\n";
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
  check.version = io::exercise_version(probe.string());
  return check;
}

std::string save_design(const std::string& folder, const DesignCheck& design) {
  const fs::path file = fs::path(folder) / (design.exercise.name + ".yaml");
  if (fs::exists(file) && !designed(read_file(file)))
    throw std::logic_error("exercise '" + design.exercise.name +
                           "' was not made by the designer (a shipped one?): save the design under another "
                           "exercise.name");
  const fs::path versions = fs::path(folder) / "versions";
  fs::create_directories(versions);
  write_file(versions / (design.exercise.name + "-" + design.version + ".yaml"), design.text);
  const fs::path partial = file.string() + ".partial";
  write_file(partial, design.text);
  fs::rename(partial, file);
  return file.string();
}

std::string design_source(const std::string& folder, const std::string& name) {
  if (!why_bad_design_name(name).empty())
    throw std::out_of_range("no exercise '" + core::printable(name) + "'");
  const fs::path file = fs::path(folder) / (name + ".yaml");
  if (!fs::is_regular_file(file)) throw std::out_of_range("no exercise '" + name + "'");
  return read_file(file);
}

}  // namespace harbour::apps
