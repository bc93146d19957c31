// The source tree's shape, read from the sources: which folder under src/harbour includes which (no folder
// includes one that includes it back, and the graph is the one docs/architecture.md gives), and no
// consumer of the simulation (image generator, network, station, console, web pages) names a machine.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "harbour/machines/MachineRegistry.h"

namespace {

namespace fs = std::filesystem;
const fs::path kSource = HARBOUR_SOURCE_DIR;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// folder -> the folders it includes, with one file that does for each
using FolderGraph = std::map<std::string, std::map<std::string, std::string>>;

FolderGraph folder_includes() {
  FolderGraph graph;
  const fs::path root = kSource / "src" / "harbour";
  const std::regex include(R"(^\s*#\s*include\s+"harbour/([^/"]+)/)");
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp" && ext != ".in")) continue;
    const fs::path relative = fs::relative(entry.path(), root);
    const std::string folder = relative.begin()->string();
    graph[folder];
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, include) && m[1] != folder)
        graph[folder].emplace(m[1], relative.string());
    }
  }
  return graph;
}

// a cycle through `folder` as "a (file) -> b (file) -> ... -> a", or "" when there is none
std::string cycle_from(const FolderGraph& graph, const std::string& start, const std::string& at,
                       std::set<std::string>& seen, const std::string& path) {
  for (const auto& [next, file] : graph.at(at)) {
    const std::string step = path + " -> " + next + " (" + file + ")";
    if (next == start) return step;
    if (!graph.contains(next) || !seen.insert(next).second) continue;
    if (std::string found = cycle_from(graph, start, next, seen, step); !found.empty()) return found;
  }
  return "";
}

TEST(SourceTree, NoFolderIncludesAFolderThatIncludesIt) {
  const FolderGraph graph = folder_includes();
  ASSERT_GT(graph.size(), 10u) << "read from " << kSource;
  for (const auto& [folder, includes] : graph) {
    std::set<std::string> seen;
    EXPECT_EQ(cycle_from(graph, folder, folder, seen, folder), "") << "a folder cycle";
  }
}

// docs/architecture.md's "Folders and what they include": one line per folder, `folder → a, b, c`
std::map<std::string, std::set<std::string>> documented_graph() {
  const std::string doc = read_text(kSource / "docs" / "architecture.md");
  const std::size_t heading = doc.find("## Folders and what they include");
  std::map<std::string, std::set<std::string>> graph;
  if (heading == std::string::npos) return graph;
  const std::size_t open = doc.find("```\n", heading), close = doc.find("```", open + 4);
  std::istringstream block(doc.substr(open + 4, close - open - 4));
  const std::string arrow = " →";
  for (std::string line; std::getline(block, line);) {
    const std::size_t at = line.find(arrow);
    if (at == std::string::npos) continue;
    std::set<std::string>& includes = graph[line.substr(0, at)];
    std::istringstream names(line.substr(at + arrow.size()));
    for (std::string name; std::getline(names >> std::ws, name, ',');)
      includes.insert(name.substr(0, name.find_last_not_of(' ') + 1));
  }
  return graph;
}

TEST(SourceTree, TheFolderGraphIsTheOneTheArchitectureGives) {
  const auto documented = documented_graph();
  ASSERT_FALSE(documented.empty()) << "docs/architecture.md has no \"Folders and what they include\"";
  const FolderGraph graph = folder_includes();
  for (const auto& [folder, includes] : graph) {
    std::set<std::string> found;
    for (const auto& [included, file] : includes)
      found.insert(included);
    ASSERT_TRUE(documented.contains(folder)) << folder << " is not in the architecture's folder graph";
    EXPECT_EQ(documented.at(folder), found)
        << folder << " (as the architecture gives it vs as its sources are)";
  }
  EXPECT_EQ(documented.size(), graph.size()) << "the architecture names a folder src/harbour lacks";
}

// the text without its comments (// to the line's end, /* ... */), lines kept where they were
std::string without_comments(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "//") == 0) {
      while (i < text.size() && text[i] != '\n')
        ++i;
    } else if (text.compare(i, 2, "/*") == 0) {
      const std::size_t end = text.find("*/", i + 2);
      for (; i < std::min(end + 1, text.size()); ++i)
        if (text[i] == '\n') out += '\n';
      continue;
    }
    if (i < text.size()) out += text[i];
  }
  return out;
}

// "reach_stacker" -> "ReachStacker"
std::string camel(std::string_view kind) {
  std::string out;
  bool up = true;
  for (const char c : kind) {
    if (c == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  return out;
}

TEST(SourceTree, NoConsumerOfTheSimulationNamesAMachine) {
  std::string kinds, types;
  for (const std::string_view kind : harbour::sim::machine_kinds()) {
    kinds += (kinds.empty() ? "" : "|") + std::string(kind);
    types += (types.empty() ? "" : "|") + camel(kind);
  }
  ASSERT_FALSE(kinds.empty());
  // a kind as a word ("sts", "reach_stacker"), or a type named after one (StsCrane, ReachStackerSetup)
  const std::regex names("\\b(" + kinds + ")\\b|\\b(" + types + ")(?=[A-Z_]|\\b)", std::regex::icase);
  int files = 0;
  for (const char* folder :
       {"src/harbour/ig", "src/harbour/net", "src/harbour/station", "src/harbour/console", "web/src"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kSource / folder)) {
      if (!entry.is_regular_file()) continue;
      ++files;
      std::istringstream code(without_comments(read_text(entry.path())));
      int line_number = 0;
      for (std::string line; std::getline(code, line);) {
        ++line_number;
        std::smatch m;
        if (std::regex_search(line, m, names))
          ADD_FAILURE() << fs::relative(entry.path(), kSource).string() << ":" << line_number << " names the "
                        << m.str() << ": " << line;
      }
    }
  }
  EXPECT_GT(files, 50);
}

}  // namespace
