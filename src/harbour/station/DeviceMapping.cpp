#include "harbour/station/DeviceMapping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace harbour::station {

double shape_axis(const Binding& b, double raw) {
  const Calibration& c = b.calibration;
  double n = 0.0;
  if (c.centered) {
    n = raw >= c.center ? (raw - c.center) / (c.max - c.center) : (raw - c.center) / (c.center - c.min);
    n = std::clamp(n, -1.0, 1.0);
  } else {
    n = std::clamp((raw - c.min) / (c.max - c.min), 0.0, 1.0);
  }
  if (!std::isfinite(n)) return 0.0;
  const double magnitude = std::abs(n);
  const double live = magnitude <= b.dead_zone ? 0.0 : (magnitude - b.dead_zone) / (1.0 - b.dead_zone);
  double shaped = (1.0 - b.expo) * live + b.expo * live * live * live;
  if (n < 0.0) shaped = -shaped;
  if (b.invert) shaped = c.centered ? -shaped : 1.0 - shaped;
  return shaped;
}

std::string why_unfit(const DeviceMapping& mapping, int device, int axes, int buttons, int hats) {
  for (const Binding& b : mapping.bindings) {
    if (b.device != device) continue;
    const auto fail = [&](const char* what, int count) {
      return mapping.file + ":" + std::to_string(b.line) + ": bindings." + b.control + ": " + what + " " +
             std::to_string(b.index) + " is beyond device '" +
             mapping.devices[static_cast<std::size_t>(device)].id + "', which has " + std::to_string(count);
    };
    if (b.source == Binding::Source::kAxis && b.index >= axes) return fail("axis", axes);
    if (b.source == Binding::Source::kButton && b.index >= buttons) return fail("button", buttons);
    if (b.source == Binding::Source::kHat && b.index >= hats) return fail("hat", hats);
  }
  return {};
}

ControlMapper::ControlMapper(const scene::ControlTable& table, DeviceMapping mapping)
    : table_(table), mapping_(std::move(mapping)) {
  was_pressed_.assign(mapping_.bindings.size(), false);
  held_since_s_.assign(mapping_.bindings.size(), std::numeric_limits<double>::quiet_NaN());
  toggled_.assign(static_cast<std::size_t>(scene::kMaxControls), 0.0);
  for (int slot = 0; slot < table_.size(); ++slot)
    toggled_[static_cast<std::size_t>(slot)] = table_[slot].neutral;
}

std::vector<std::string> ControlMapper::controls_of(int device) const {
  std::vector<std::string> labels;
  for (const Binding& b : mapping_.bindings)
    if (b.device == device && std::find(labels.begin(), labels.end(), b.control) == labels.end())
      labels.push_back(b.control);
  return labels;
}

scene::Controls ControlMapper::map(const std::vector<DeviceState>& devices, const std::vector<bool>& keyboard,
                                   double now_s) {
  scene::Controls c = table_.neutral();
  std::array<bool, scene::kMaxControls> lost{};
  std::array<double, scene::kMaxControls> deflection{};  // the strongest contribution to each axis so far
  const auto key = [&](int code) {
    return code >= 0 && static_cast<std::size_t>(code) < keyboard.size() && keyboard[code];
  };
  for (std::size_t i = 0; i < mapping_.bindings.size(); ++i) {
    const Binding& b = mapping_.bindings[i];
    const auto slot = static_cast<std::size_t>(b.slot);
    const scene::ControlSpec& spec = table_[b.slot];
    const DeviceMatch& match = mapping_.devices[static_cast<std::size_t>(b.device)];
    const DeviceState* state = nullptr;
    if (!match.keyboard) {  // a joystick, or the mouse (a state the input fills while there is a window)
      state = static_cast<std::size_t>(b.device) < devices.size()
                  ? &devices[static_cast<std::size_t>(b.device)]
                  : nullptr;
      const bool present =
          state && state->connected &&
          (b.source != Binding::Source::kAxis || static_cast<std::size_t>(b.index) < state->axes.size()) &&
          (b.source != Binding::Source::kButton ||
           static_cast<std::size_t>(b.index) < state->buttons.size()) &&
          (b.source != Binding::Source::kHat || static_cast<std::size_t>(b.index) < state->hats.size());
      if (!present) {
        if (!match.mouse) lost[slot] = true;  // no window (yet) is not a lost device
        continue;
      }
    }
    // the physical reading: an axis position, or whether a button, hat direction or key is held
    double axis = 0.0;
    bool pressed = false;
    switch (b.source) {
      case Binding::Source::kAxis:
        axis = shape_axis(b, state->axes[static_cast<std::size_t>(b.index)]);
        pressed = axis > 0.5;
        break;
      case Binding::Source::kButton:
        pressed = match.keyboard ? key(b.index) : state->buttons[static_cast<std::size_t>(b.index)];
        break;
      case Binding::Source::kHat:
        pressed = (state->hats[static_cast<std::size_t>(b.index)] & b.hat_direction) != 0;
        break;
      case Binding::Source::kKeys:
        axis = (key(b.keys[0]) ? b.value : 0.0) - (key(b.keys[1]) ? b.value : 0.0);
        pressed = axis > 0.5;
        break;
    }
    // a deliberate press: held hold_s before it counts
    if (!pressed)
      held_since_s_[i] = std::numeric_limits<double>::quiet_NaN();
    else if (std::isnan(held_since_s_[i]))
      held_since_s_[i] = now_s;
    if (b.hold_s > 0.0 && b.source != Binding::Source::kAxis && !(now_s - held_since_s_[i] >= b.hold_s))
      pressed = false;
    switch (spec.kind) {
      case scene::ControlKind::kAxis: {
        double v = spec.neutral;
        if (b.source == Binding::Source::kAxis)
          v = b.calibration.centered ? spec.min + (axis + 1.0) / 2.0 * (spec.max - spec.min)
                                     : spec.min + axis * (spec.max - spec.min);
        else if (b.source == Binding::Source::kKeys)
          v = std::clamp(axis, spec.min, spec.max);
        else if (pressed)
          v = std::clamp(b.value, spec.min, spec.max);
        if (std::abs(v - spec.neutral) > deflection[slot]) {
          deflection[slot] = std::abs(v - spec.neutral);
          c.value[slot] = v;
        }
        break;
      }
      case scene::ControlKind::kButton:
        if (pressed) c.value[slot] = 1.0;
        break;
      case scene::ControlKind::kSwitch: {
        const double last = static_cast<double>(spec.positions.size()) - 1.0;
        if (b.source == Binding::Source::kAxis && !b.detents.empty()) {
          std::size_t nearest = 0;
          for (std::size_t d = 1; d < b.detents.size(); ++d)
            if (std::abs(axis - b.detents[d]) < std::abs(axis - b.detents[nearest])) nearest = d;
          c.value[slot] = std::min(static_cast<double>(nearest), last);
        } else if (b.toggle) {
          if (pressed && !was_pressed_[i])
            toggled_[slot] = toggled_[slot] >= last ? 0.0 : toggled_[slot] + 1.0;
          c.value[slot] = toggled_[slot];
        } else {  // a button, hat or key selecting a position: the selector stays where it was put
          if (pressed) toggled_[slot] = std::clamp(std::round(b.value), 0.0, last);
          c.value[slot] = toggled_[slot];
        }
        break;
      }
    }
    was_pressed_[i] = pressed;
  }
  // a control whose device is gone reads safe at once: the drives ramp to a stop, nothing stays pressed
  for (int slot = 0; slot < table_.size(); ++slot)
    if (lost[static_cast<std::size_t>(slot)]) c.value[static_cast<std::size_t>(slot)] = table_[slot].safe;
  return c;
}

}  // namespace harbour::station
