#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include <yaml-cpp/yaml.h>

#include "harbour/core/Vec3.h"
#include "harbour/io/DataError.h"

namespace harbour::io {

/// A parsed YAML data file with typed, range-checked field access; every failure is a DataError
/// naming file, line and field path (e.g. "materials[2].angle_of_repose_deg").
///
/// Strict: one document, no duplicate keys, and (check_unknown_keys) no key the loader never asked for, so a
/// typo is an error instead of a silently different exercise.
class YamlFile {
 public:
  /// Largest data file read [bytes]: far above any real one, small enough that a wrong path (a device, a
  /// log) cannot exhaust memory.
  static constexpr std::size_t kMaxFileBytes = 4 << 20;

  /// Reads and parses `path` (a regular file of at most kMaxFileBytes).
  static YamlFile load(const std::string& path);
  /// Parses `text` as if read from a file named `name` (tests, inline models).
  static YamlFile parse(const std::string& text, const std::string& name);

  const YAML::Node& root() const { return root_; }
  const std::string& name() const { return name_; }

  /// Throws a DataError at `node`'s line.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& problem) const;

  /// The map entry `key` of `map`; fails if missing.
  YAML::Node required(const YAML::Node& map, const std::string& key, const std::string& path) const;
  /// The map entry `key` of `map`, or nullopt when it is absent or empty; fails when `map` is not a mapping.
  std::optional<YAML::Node> optional(const YAML::Node& map, const std::string& key,
                                     const std::string& path) const;
  /// Like optional() for an entry that must be a mapping when present.
  std::optional<YAML::Node> optional_map(const YAML::Node& map, const std::string& key,
                                         const std::string& path) const;
  /// Like required() for an entry that must be a mapping.
  YAML::Node required_map(const YAML::Node& map, const std::string& key, const std::string& path) const;
  /// A finite number in [min, max] (open at `exclusive` bounds when set).
  double number(const YAML::Node& map, const std::string& key, const std::string& path, double min,
                double max, bool exclusive_min = false, bool exclusive_max = false) const;
  /// Like number() but returns `fallback` when the key is absent.
  double number_or(const YAML::Node& map, const std::string& key, const std::string& path, double fallback,
                   double min, double max, bool exclusive_min = false, bool exclusive_max = false) const;
  /// A whole number in [min, max].
  int integer(const YAML::Node& map, const std::string& key, const std::string& path, int min, int max) const;
  /// true or false, `fallback` when the key is absent.
  bool flag(const YAML::Node& map, const std::string& key, const std::string& path, bool fallback) const;
  /// A number read from a list item or other bare node (errors name `field`).
  double number_at(const YAML::Node& node, const std::string& field) const { return to_number(node, field); }
  /// A name: non-empty, at most core::kMaxNameBytes, valid UTF-8, no control characters.
  std::string text(const YAML::Node& map, const std::string& key, const std::string& path) const;
  /// A list of three finite numbers [x, y, z], each within [-limit, limit].
  core::Vec3 vector3(const YAML::Node& node, const std::string& field, double limit = 1e4) const;
  /// A sequence (possibly empty) of at most `max_items`.
  YAML::Node sequence(const YAML::Node& map, const std::string& key, const std::string& path,
                      std::size_t max_items = 10000) const;

  /// A section of `map` that another reader reads (a machine file's looks, read by the image generator): this
  /// file's check_unknown_keys passes over it.
  void read_elsewhere(const YAML::Node& map, const std::string& key, const std::string& path) const;

  /// Fails at the first mapping key in the file that no accessor above asked for, naming the keys that its
  /// mapping may hold. Loaders call it once they have read everything.
  void check_unknown_keys() const;
  /// The same for the keys under `node` (at `path`) alone: a reader of one section of a file.
  void check_unknown_keys(const YAML::Node& node, const std::string& path) const;

 private:
  YamlFile(YAML::Node root, std::string name) : root_(std::move(root)), name_(std::move(name)) {}
  double to_number(const YAML::Node& node, const std::string& field) const;
  void asked(const YAML::Node& map, const std::string& key) const;
  void check_keys_under(const YAML::Node& node, const std::string& path, int depth) const;

  YAML::Node root_;
  std::string name_;
  /// keys asked for, by the position of their mapping in the text (a mapping's identity)
  mutable std::map<std::size_t, std::set<std::string>> asked_;
  /// sections another reader reads, by their position in the text
  mutable std::set<std::size_t> read_elsewhere_;
};

}  // namespace harbour::io
