#pragma once

#include <string>
#include <vector>

#include "harbour/io/YamlFile.h"

namespace harbour::io {

/// A team exercise (data/teams/*.yaml): several stations in one harbour, each member simulating its own
/// machine in its own exercise. The exercises share the harbour's frame (the quay surface z = 0, the quay
/// edge along y, water at +x), so each member's machine stands where its exercise puts it.
struct TeamRole {
  std::string role;           ///< "crane", "tractor-1": letters, digits, '-', '_' (1-32)
  std::string exercise_file;  ///< the member's exercise
  /// A crane's team trucks (its exercise's `trucks: {team: true}` lane), in order: the roles whose trailers
  /// they are.
  std::vector<std::string> trucks;
};
struct Team {
  std::string name;  ///< the team session's name on the network (1-64 letters, digits, '-', '_', '.')
  std::vector<TeamRole> roles;
  /// The role named `role`, or nullptr.
  const TeamRole* find(const std::string& role) const;
  /// The roles as "crane, tractor".
  std::string role_list() const;
};

/// Reads a team file: its name, 2-8 roles with distinct names, each an exercise's name (looked up in
/// `exercise_folders` in order) or a path relative to the team file's folder. Every error is a DataError
/// naming the file, the line and the field.
Team load_team(const YamlFile& file, const std::string& folder,
               const std::vector<std::string>& exercise_folders);
Team load_team(const std::string& path, const std::vector<std::string>& exercise_folders);

}  // namespace harbour::io
