#pragma once

#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "harbour/core/Vec3.h"
#include "harbour/io/DataError.h"

namespace harbour::io {

/// A parsed YAML data file with typed, range-checked field access; every failure is a DataError
/// naming file, line and field path (e.g. "materials[2].angle_of_repose_deg").
class YamlFile {
 public:
  /// Reads and parses `path`.
  static YamlFile load(const std::string& path);
  /// Parses `text` as if read from a file named `name` (tests, inline models).
  static YamlFile parse(const std::string& text, const std::string& name);

  const YAML::Node& root() const { return root_; }
  const std::string& name() const { return name_; }

  /// Throws a DataError at `node`'s line.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& problem) const;

  /// The map entry `key` of `map`; fails if missing.
  YAML::Node required(const YAML::Node& map, const std::string& key, const std::string& path) const;
  /// A finite number in [min, max] (open at `exclusive` bounds when set).
  double number(const YAML::Node& map, const std::string& key, const std::string& path, double min,
                double max, bool exclusive_min = false, bool exclusive_max = false) const;
  /// Like number() but returns `fallback` when the key is absent.
  double number_or(const YAML::Node& map, const std::string& key, const std::string& path, double fallback,
                   double min, double max, bool exclusive_min = false, bool exclusive_max = false) const;
  /// A whole number in [min, max].
  int integer(const YAML::Node& map, const std::string& key, const std::string& path, int min, int max) const;
  /// A non-empty string.
  std::string text(const YAML::Node& map, const std::string& key, const std::string& path) const;
  /// A list of three finite numbers [x, y, z].
  core::Vec3 vector3(const YAML::Node& node, const std::string& field) const;
  /// A sequence (possibly empty).
  YAML::Node sequence(const YAML::Node& map, const std::string& key, const std::string& path) const;

 private:
  YamlFile(YAML::Node root, std::string name) : root_(std::move(root)), name_(std::move(name)) {}
  double to_number(const YAML::Node& node, const std::string& field) const;

  YAML::Node root_;
  std::string name_;
};

}  // namespace harbour::io
