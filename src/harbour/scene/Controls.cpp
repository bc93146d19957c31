#include "harbour/scene/Controls.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace harbour::scene {

const char* to_string(ControlKind kind) {
  switch (kind) {
    case ControlKind::kAxis:
      return "axis";
    case ControlKind::kButton:
      return "button";
    case ControlKind::kSwitch:
      return "switch";
  }
  return "?";
}

namespace {
// the range a control's value lives in
std::pair<double, double> range_of(const ControlSpec& c) {
  switch (c.kind) {
    case ControlKind::kAxis:
      return {c.min, c.max};
    case ControlKind::kButton:
      return {0.0, 1.0};
    case ControlKind::kSwitch:
      return {0.0, static_cast<double>(c.positions.size()) - 1.0};
  }
  return {0.0, 0.0};
}

double read_value(const ControlSpec& c, double v) {
  if (!std::isfinite(v)) return c.neutral;
  switch (c.kind) {
    case ControlKind::kAxis:
      return std::clamp(v, c.min, c.max);
    case ControlKind::kButton:
      return v != 0.0 ? 1.0 : 0.0;
    case ControlKind::kSwitch:
      return std::clamp(std::round(v), 0.0, static_cast<double>(c.positions.size()) - 1.0);
  }
  return c.neutral;
}
}  // namespace

ControlTable::ControlTable(std::vector<ControlSpec> controls) : controls_(std::move(controls)) {
  if (controls_.size() > static_cast<std::size_t>(kMaxControls))
    throw std::invalid_argument("a machine has at most " + std::to_string(kMaxControls) + " controls, not " +
                                std::to_string(controls_.size()));
  for (std::size_t n = 0; n < controls_.size(); ++n) {
    const ControlSpec& c = controls_[n];
    const std::string name = "control '" + c.label + "'";
    if (c.label.empty()) throw std::invalid_argument("control " + std::to_string(n + 1) + " has no label");
    for (std::size_t k = 0; k < n; ++k)
      if (controls_[k].label == c.label) throw std::invalid_argument(name + " is declared twice");
    if (c.kind == ControlKind::kAxis && !(std::isfinite(c.min) && std::isfinite(c.max) && c.min < c.max))
      throw std::invalid_argument(name + ": an axis needs min < max");
    if (c.kind == ControlKind::kSwitch && c.positions.size() < 2)
      throw std::invalid_argument(name + ": a switch has at least two positions");
    const auto [low, high] = range_of(c);
    for (const double v : {c.neutral, c.safe})
      if (!(v >= low && v <= high) || read_value(c, v) != v)
        throw std::invalid_argument(name + ": neutral and safe values must be values it can take");
  }
}

int ControlTable::find(std::string_view label) const {
  for (std::size_t n = 0; n < controls_.size(); ++n)
    if (controls_[n].label == label) return static_cast<int>(n);
  return -1;
}

int ControlTable::slot(std::string_view label, ControlKind kind) const {
  const int n = find(label);
  if (n < 0) throw std::invalid_argument("the machine needs a control '" + std::string(label) + "'");
  if (controls_[static_cast<std::size_t>(n)].kind != kind)
    throw std::invalid_argument("control '" + std::string(label) + "' must be a " + to_string(kind) +
                                ", not a " + to_string(controls_[static_cast<std::size_t>(n)].kind));
  return n;
}

Controls ControlTable::neutral() const {
  Controls c;
  for (std::size_t n = 0; n < controls_.size(); ++n)
    c.value[n] = controls_[n].neutral;
  return c;
}

Controls ControlTable::safe() const {
  Controls c;
  for (std::size_t n = 0; n < controls_.size(); ++n)
    c.value[n] = controls_[n].safe;
  return c;
}

Controls ControlTable::in_range(const Controls& controls) const {
  Controls r;
  for (std::size_t n = 0; n < controls_.size(); ++n)
    r.value[n] = read_value(controls_[n], controls.value[n]);
  return r;
}

}  // namespace harbour::scene
