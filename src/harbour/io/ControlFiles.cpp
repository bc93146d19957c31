#include "harbour/io/ControlFiles.h"

#include <algorithm>
#include <stdexcept>

#include "harbour/core/Text.h"

namespace harbour::io {

namespace {
std::string item_path(const std::string& path, std::size_t n) {
  return path + ".controls[" + std::to_string(n) + "]";
}

// a switch position given by name: its index
double position_of(const YamlFile& f, const YAML::Node& entry, const std::string& key, const std::string& at,
                   const scene::ControlSpec& c) {
  if (!f.optional(entry, key, at)) return 0.0;
  const std::string name = f.text(entry, key, at);
  const auto p = std::find(c.positions.begin(), c.positions.end(), name);
  if (p == c.positions.end())
    f.fail(entry[key], at + "." + key, "'" + name + "' is not one of its positions");
  return static_cast<double>(p - c.positions.begin());
}
}  // namespace

scene::ControlTable read_control_table(const YamlFile& f, const YAML::Node& parent, const std::string& path) {
  const YAML::Node list = f.sequence(parent, "controls", path, scene::kMaxControls);
  std::vector<scene::ControlSpec> specs;
  for (std::size_t n = 0; n < list.size(); ++n) {
    const YAML::Node entry = list[n];
    const std::string at = item_path(path, n);
    if (!entry.IsMap()) f.fail(entry, at, "expected a mapping (label, kind, ...)");
    scene::ControlSpec c;
    c.label = f.text(entry, "label", at);
    if (const std::string bad = core::why_bad_name(c.label, 64);
        !bad.empty() || c.label.find(' ') != std::string::npos)
      f.fail(entry["label"], at + ".label", "a label is one word of at most 64 bytes");
    for (std::size_t k = 0; k < specs.size(); ++k)
      if (specs[k].label == c.label)
        f.fail(entry["label"], at + ".label", "'" + c.label + "' is declared twice");
    const std::string kind = f.text(entry, "kind", at);
    c.meaning = f.optional(entry, "meaning", at) ? f.text(entry, "meaning", at) : "";
    if (kind == "axis") {
      c.kind = scene::ControlKind::kAxis;
      c.min = f.number_or(entry, "min", at, -1.0, -1e6, 1e6);
      c.max = f.number_or(entry, "max", at, 1.0, -1e6, 1e6);
      if (!(c.min < c.max)) f.fail(entry, at + ".max", "must be above min");
      const double rest = std::clamp(0.0, c.min, c.max);
      c.neutral = f.number_or(entry, "neutral", at, rest, c.min, c.max);
      c.safe = f.number_or(entry, "safe", at, c.neutral, c.min, c.max);
    } else if (kind == "button") {
      c.kind = scene::ControlKind::kButton;
      c.min = 0.0;
      c.max = 1.0;
    } else if (kind == "switch") {
      c.kind = scene::ControlKind::kSwitch;
      const YAML::Node positions = f.sequence(entry, "positions", at, 16);
      if (positions.size() < 2) f.fail(positions, at + ".positions", "a switch has at least two positions");
      for (std::size_t k = 0; k < positions.size(); ++k) {
        const YAML::Node p = positions[k];
        const std::string field = at + ".positions[" + std::to_string(k) + "]";
        if (!p.IsScalar()) f.fail(p, field, "expected a position name");
        const std::string name = p.Scalar();
        if (!core::why_bad_name(name, 64).empty()) f.fail(p, field, "a position name of at most 64 bytes");
        if (std::find(c.positions.begin(), c.positions.end(), name) != c.positions.end())
          f.fail(p, field, "'" + name + "' is listed twice");
        c.positions.push_back(name);
      }
      c.min = 0.0;
      c.max = static_cast<double>(c.positions.size() - 1);
      c.neutral = position_of(f, entry, "neutral", at, c);
      c.safe = f.optional(entry, "safe", at) ? position_of(f, entry, "safe", at, c) : c.neutral;
    } else {
      f.fail(entry["kind"], at + ".kind", "'" + kind + "' is not axis, button or switch");
    }
    specs.push_back(std::move(c));
  }
  try {
    return scene::ControlTable(std::move(specs));
  } catch (const std::invalid_argument& e) {
    f.fail(list, path + ".controls", e.what());
  }
}

}  // namespace harbour::io
