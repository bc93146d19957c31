#include "harbour/io/YamlFile.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace harbour::io {
namespace {

std::string describe(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

YamlFile YamlFile::parse(const std::string& text, const std::string& name) {
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw DataError(name, 1, "(document)", "expected a mapping at the top level");
    return YamlFile(root, name);
  } catch (const YAML::Exception& e) {
    throw DataError(name, e.mark.line + 1, "(syntax)", e.msg);
  }
}

YamlFile YamlFile::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw DataError(path, 0, "(file)", "cannot be opened");
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

void YamlFile::fail(const YAML::Node& node, const std::string& field, const std::string& problem) const {
  throw DataError(name_, node.Mark().line + 1, field, problem);
}

YAML::Node YamlFile::required(const YAML::Node& map, const std::string& key, const std::string& path) const {
  const std::string field = path.empty() ? key : path + "." + key;
  if (!map.IsMap()) fail(map, path, "expected a mapping");
  YAML::Node node = map[key];
  if (!node.IsDefined() || node.IsNull()) fail(map, field, "missing");
  return node;
}

double YamlFile::to_number(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar()) fail(node, field, "expected a number");
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(node, field, "'" + node.Scalar() + "' is not a number");
  }
  if (!std::isfinite(value)) fail(node, field, "'" + node.Scalar() + "' is not a finite number");
  return value;
}

double YamlFile::number(const YAML::Node& map, const std::string& key, const std::string& path, double min,
                        double max, bool exclusive_min, bool exclusive_max) const {
  const std::string field = path.empty() ? key : path + "." + key;
  const YAML::Node node = required(map, key, path);
  const double value = to_number(node, field);
  const bool low = exclusive_min ? value <= min : value < min;
  const bool high = exclusive_max ? value >= max : value > max;
  if (low || high)
    fail(node, field,
         describe(value) + " is outside " + (exclusive_min ? "(" : "[") + describe(min) + ", " +
             describe(max) + (exclusive_max ? ")" : "]"));
  return value;
}

double YamlFile::number_or(const YAML::Node& map, const std::string& key, const std::string& path,
                           double fallback, double min, double max, bool exclusive_min,
                           bool exclusive_max) const {
  if (!map.IsMap() || !map[key].IsDefined()) return fallback;
  return number(map, key, path, min, max, exclusive_min, exclusive_max);
}

int YamlFile::integer(const YAML::Node& map, const std::string& key, const std::string& path, int min,
                      int max) const {
  const double value = number(map, key, path, min, max);
  if (value != std::floor(value)) fail(required(map, key, path), path + "." + key, "must be a whole number");
  return static_cast<int>(value);
}

std::string YamlFile::text(const YAML::Node& map, const std::string& key, const std::string& path) const {
  const std::string field = path.empty() ? key : path + "." + key;
  const YAML::Node node = required(map, key, path);
  if (!node.IsScalar() || node.Scalar().empty()) fail(node, field, "expected a non-empty string");
  return node.Scalar();
}

core::Vec3 YamlFile::vector3(const YAML::Node& node, const std::string& field) const {
  if (!node.IsSequence() || node.size() != 3) fail(node, field, "expected a list of three numbers [x, y, z]");
  return {to_number(node[0], field + "[0]"), to_number(node[1], field + "[1]"),
          to_number(node[2], field + "[2]")};
}

YAML::Node YamlFile::sequence(const YAML::Node& map, const std::string& key, const std::string& path) const {
  const std::string field = path.empty() ? key : path + "." + key;
  const YAML::Node node = required(map, key, path);
  if (!node.IsSequence()) fail(node, field, "expected a list");
  return node;
}

}  // namespace harbour::io
