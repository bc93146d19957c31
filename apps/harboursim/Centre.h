#pragma once

#include <string>
#include <vector>

namespace harbour::apps {

/// A training centre's own folders: the exercises its designer saves and the routes its instructors write,
/// searched by name before the shipped data/exercises and data/routes ("" : none of its own).
struct CentreFolders {
  std::string exercises;
  std::string routes;

  /// The centre's folder (when it has one), then the shipped one.
  std::vector<std::string> exercise_folders() const {
    return with_shipped(exercises, std::string(HARBOUR_DATA_DIR) + "/exercises");
  }
  std::vector<std::string> route_folders() const {
    return with_shipped(routes, std::string(HARBOUR_DATA_DIR) + "/routes");
  }

 private:
  static std::vector<std::string> with_shipped(const std::string& own, const std::string& shipped) {
    if (own.empty()) return {shipped};
    return {own, shipped};
  }
};

}  // namespace harbour::apps
