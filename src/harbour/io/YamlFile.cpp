#include "harbour/io/YamlFile.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>

#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"

namespace harbour::io {
namespace {

// deeper nesting than any data file needs; yaml-cpp itself stops at its own depth limit
constexpr int kMaxDepth = 64;

std::string describe(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

int line_of(const YAML::Node& node) {
  return node.Mark().line + 1;
}

// How many nodes a file may hold for its size: every node takes at least one byte of text, twice over for
// flow mappings' implicit values ("{a, b}"). More means aliases (*name) repeat anchored nodes: a few lines of
// nested aliases (a "billion laughs") expand to billions, and every reader would walk them all.
std::size_t node_budget(std::size_t text_bytes) {
  return 2 * text_bytes + 1024;
}

struct AliasBudgetSpent {};

// 1-based line of the first alias (*name) in `text`, 0 if none (a '*' opening a plain token outside quotes
// and comments)
int first_alias_line(const std::string& text) {
  int line = 1;
  char quote = 0;
  bool comment = false;
  for (std::size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (c == '\n') {
      ++line;
      comment = false;
      if (quote == '\'') quote = 0;  // a stray quote does not hide the rest of the file
      continue;
    }
    if (comment) continue;
    if (quote) {
      if (c == quote) quote = 0;
      continue;
    }
    const char before = at == 0 ? ' ' : text[at - 1];
    const bool token_start = before == ' ' || before == '\t' || before == '[' || before == '{' ||
                             before == ',' || before == '\n' || before == '-' || before == ':';
    if (c == '#' && (before == ' ' || before == '\t' || before == '\n')) comment = true;
    if ((c == '"' || c == '\'') && token_start) quote = c;
    if (c == '*' && token_start && at + 1 < text.size() && text[at + 1] != ' ') return line;
  }
  return 0;
}

// duplicate keys (yaml-cpp keeps both and reads the first), keys that are not plain names, too deep nesting,
// aliases expanding past the file's node budget (`budget`: nodes still allowed, counted down)
void check_structure(const YAML::Node& node, const std::string& file, const std::string& path, int depth,
                     std::size_t& budget) {
  if (depth > kMaxDepth) throw DataError(file, line_of(node), path, "nested too deeply");
  if (budget == 0) throw AliasBudgetSpent{};
  --budget;
  if (node.IsSequence()) {
    for (std::size_t n = 0; n < node.size(); ++n)
      check_structure(node[n], file, path + "[" + std::to_string(n) + "]", depth + 1, budget);
  } else if (node.IsMap()) {
    std::map<std::string, int> seen;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar())
        throw DataError(file, line_of(entry.first), path,
                        "a key must be a plain name, not a list or mapping");
      const std::string& key = entry.first.Scalar();
      const auto [first, inserted] = seen.emplace(key, line_of(entry.first));
      if (!inserted)
        throw DataError(file, line_of(entry.first), join(path, key),
                        "duplicate key (first given at line " + std::to_string(first->second) + ")");
      check_structure(entry.second, file, join(path, key), depth + 1, budget);
    }
  }
}

// 1-based line of a second YAML document's marker ("---" or "..." at the start of a line after content, or a
// second "---"), 0 if there is none. (yaml-cpp 0.7's LoadAll loops for ever on a document that starts with a
// stray ',', so the documents are found here and the one document is parsed with Load.)
int second_document_line(const std::string& text) {
  bool content = false, ended = false;
  int line = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view row(text.data() + at, end - at);
    ++line;
    const auto marker = [&](std::string_view m) {
      return row.substr(0, 3) == m && (row.size() == 3 || row[3] == ' ' || row[3] == '\t' || row[3] == '\r');
    };
    if (marker("---")) {
      if (content || ended) return line;
    } else if (marker("...")) {
      ended = true;  // the document ends: nothing may follow
    } else if (const auto first = row.find_first_not_of(" \t\r");
               first != std::string_view::npos && row[first] != '#') {
      if (ended) return line;
      content = true;
    }
    at = end + 1;
  }
  return 0;
}

}  // namespace

YamlFile YamlFile::parse(const std::string& text, const std::string& name) {
  if (const int line = second_document_line(text); line > 0)
    throw DataError(name, line, "(document)", "a second YAML document: a data file holds exactly one");
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw DataError(name, e.mark.line + 1, "(syntax)", e.msg);
  }
  if (!root.IsDefined() || root.IsNull()) throw DataError(name, 1, "(document)", "the file is empty");
  if (!root.IsMap()) throw DataError(name, 1, "(document)", "expected a mapping at the top level");
  std::size_t budget = node_budget(text.size());
  try {
    check_structure(root, name, "", 0, budget);
  } catch (const AliasBudgetSpent&) {
    const int line = first_alias_line(text);
    throw DataError(name, line > 0 ? line : 1, "(aliases)",
                    "aliases (*name) repeat anchored nodes past " + std::to_string(node_budget(text.size())) +
                        " nodes, more than a file of " + std::to_string(text.size()) +
                        " bytes holds: refused (nested aliases grow exponentially)");
  }
  return YamlFile(root, name);
}

YamlFile YamlFile::load(const std::string& path) {
  std::string why;
  const std::optional<std::string> text = read_bounded_file(path, kMaxFileBytes, why);
  if (!text) throw DataError(path, 0, "(file)", why);
  return parse(*text, path);
}

void YamlFile::fail(const YAML::Node& node, const std::string& field, const std::string& problem) const {
  throw DataError(name_, line_of(node), field, problem);
}

void YamlFile::asked(const YAML::Node& map, const std::string& key) const {
  asked_[map.Mark().pos].insert(key);
}

std::optional<YAML::Node> YamlFile::optional(const YAML::Node& map, const std::string& key,
                                             const std::string& path) const {
  if (!map.IsMap()) fail(map, path, "expected a mapping");
  asked(map, key);
  const YAML::Node node = map[key];
  if (!node.IsDefined() || node.IsNull()) return std::nullopt;
  return node;
}

std::optional<YAML::Node> YamlFile::optional_map(const YAML::Node& map, const std::string& key,
                                                 const std::string& path) const {
  std::optional<YAML::Node> node = optional(map, key, path);
  if (node && !node->IsMap()) fail(*node, join(path, key), "expected a mapping");
  return node;
}

YAML::Node YamlFile::required(const YAML::Node& map, const std::string& key, const std::string& path) const {
  const std::optional<YAML::Node> node = optional(map, key, path);
  if (!node) fail(map, join(path, key), "missing");
  return *node;
}

YAML::Node YamlFile::required_map(const YAML::Node& map, const std::string& key,
                                  const std::string& path) const {
  const YAML::Node node = required(map, key, path);
  if (!node.IsMap()) fail(node, join(path, key), "expected a mapping");
  return node;
}

double YamlFile::to_number(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar()) fail(node, field, "expected a number");
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(node, field, "'" + core::printable(node.Scalar(), 40) + "' is not a number");
  }
  if (!std::isfinite(value))
    fail(node, field, "'" + core::printable(node.Scalar(), 40) + "' is not a finite number");
  return value;
}

double YamlFile::number(const YAML::Node& map, const std::string& key, const std::string& path, double min,
                        double max, bool exclusive_min, bool exclusive_max) const {
  const std::string field = join(path, key);
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
  if (!optional(map, key, path)) return fallback;
  return number(map, key, path, min, max, exclusive_min, exclusive_max);
}

int YamlFile::integer(const YAML::Node& map, const std::string& key, const std::string& path, int min,
                      int max) const {
  const double value = number(map, key, path, min, max);
  if (value != std::floor(value)) fail(required(map, key, path), join(path, key), "must be a whole number");
  return static_cast<int>(value);
}

bool YamlFile::flag(const YAML::Node& map, const std::string& key, const std::string& path,
                    bool fallback) const {
  const std::optional<YAML::Node> node = optional(map, key, path);
  if (!node) return fallback;
  if (node->IsScalar() && (node->Scalar() == "true" || node->Scalar() == "false"))
    return node->Scalar() == "true";
  fail(*node, join(path, key), "expected true or false");
}

std::string YamlFile::text(const YAML::Node& map, const std::string& key, const std::string& path) const {
  const std::string field = join(path, key);
  const YAML::Node node = required(map, key, path);
  if (!node.IsScalar()) fail(node, field, "expected a name");
  if (const std::string why = core::why_bad_name(node.Scalar()); !why.empty())
    fail(node, field, "the name " + why);
  return node.Scalar();
}

core::Vec3 YamlFile::vector3(const YAML::Node& node, const std::string& field, double limit) const {
  if (!node.IsSequence() || node.size() != 3) fail(node, field, "expected a list of three numbers [x, y, z]");
  core::Vec3 v;
  double* parts[] = {&v.x, &v.y, &v.z};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string at = field + "[" + std::to_string(k) + "]";
    *parts[k] = to_number(node[k], at);
    if (std::abs(*parts[k]) > limit)
      fail(node[k], at,
           describe(*parts[k]) + " is outside [" + describe(-limit) + ", " + describe(limit) + "]");
  }
  return v;
}

YAML::Node YamlFile::sequence(const YAML::Node& map, const std::string& key, const std::string& path,
                              std::size_t max_items) const {
  const std::string field = join(path, key);
  const YAML::Node node = required(map, key, path);
  if (!node.IsSequence()) fail(node, field, "expected a list");
  if (node.size() > max_items)
    fail(node, field,
         std::to_string(node.size()) + " items, more than the " + std::to_string(max_items) + " allowed");
  return node;
}

void YamlFile::check_keys_under(const YAML::Node& node, const std::string& path, int depth) const {
  if (depth > kMaxDepth) return;  // check_structure refused deeper files already
  if (read_elsewhere_.count(node.Mark().pos)) return;
  if (node.IsSequence()) {
    for (std::size_t n = 0; n < node.size(); ++n)
      check_keys_under(node[n], path + "[" + std::to_string(n) + "]", depth + 1);
    return;
  }
  if (!node.IsMap()) return;
  const auto known = asked_.find(node.Mark().pos);
  for (const auto& entry : node) {
    const std::string& key = entry.first.Scalar();
    if (known == asked_.end() || !known->second.count(key)) {
      std::string list;
      if (known != asked_.end())
        for (const std::string& k : known->second)
          list += (list.empty() ? "" : ", ") + k;
      fail(entry.first, join(path, key),
           "unknown key '" + core::printable(key, 60) + "'" +
               (list.empty() ? std::string(" (nothing is read here)") : " (known here: " + list + ")"));
    }
    check_keys_under(entry.second, join(path, key), depth + 1);
  }
}

void YamlFile::read_elsewhere(const YAML::Node& map, const std::string& key, const std::string& path) const {
  if (const std::optional<YAML::Node> section = optional(map, key, path))
    read_elsewhere_.insert(section->Mark().pos);
}

void YamlFile::check_unknown_keys() const {
  check_keys_under(root_, "", 0);
}

void YamlFile::check_unknown_keys(const YAML::Node& node, const std::string& path) const {
  check_keys_under(node, path, 0);
}

}  // namespace harbour::io
