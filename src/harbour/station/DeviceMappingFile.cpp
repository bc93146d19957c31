#include "harbour/station/DeviceMappingFile.h"

#include <SDL.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <sstream>

namespace harbour::station {

namespace {

int scancode(const io::YamlFile& f, const YAML::Node& node, const std::string& field) {
  if (!node.IsScalar()) f.fail(node, field, "expected a key name (SDL's: A, Space, Left, Keypad 8, ...)");
  const SDL_Scancode code = SDL_GetScancodeFromName(node.Scalar().c_str());
  if (code == SDL_SCANCODE_UNKNOWN) f.fail(node, field, "'" + node.Scalar() + "' is not a key SDL knows");
  return static_cast<int>(code);
}

int hat_direction(const io::YamlFile& f, const YAML::Node& entry, const std::string& at) {
  const std::string d = f.text(entry, "direction", at);
  if (d == "up") return SDL_HAT_UP;
  if (d == "right") return SDL_HAT_RIGHT;
  if (d == "down") return SDL_HAT_DOWN;
  if (d == "left") return SDL_HAT_LEFT;
  f.fail(entry["direction"], at + ".direction", "'" + d + "' is not up, right, down or left");
}

Calibration read_calibration(const io::YamlFile& f, const YAML::Node& entry, const std::string& at) {
  Calibration c;
  const auto node = f.optional_map(entry, "calibration", at);
  if (!node) return c;
  const std::string cat = at + ".calibration";
  c.min = f.number(*node, "min", cat, -1e6, 1e6);
  c.max = f.number(*node, "max", cat, -1e6, 1e6);
  c.centered = f.optional(*node, "center", cat).has_value();
  if (c.centered) {
    c.center = f.number(*node, "center", cat, -1e6, 1e6);
    if (!(c.min < c.center && c.center < c.max)) f.fail(*node, cat, "needs min < center < max");
  } else if (!(c.min < c.max)) {
    f.fail(*node, cat + ".min", "min must be below max");
  }
  return c;
}

}  // namespace

DeviceMapping load_device_mapping(const io::YamlFile& f, const sim::ControlTable& table) {
  DeviceMapping m;
  m.file = f.name();
  const YAML::Node root = f.required_map(f.root(), "mapping", "");
  m.name = f.text(root, "name", "mapping");
  const YAML::Node devices = f.sequence(root, "devices", "mapping", 16);
  for (std::size_t n = 0; n < devices.size(); ++n) {
    const std::string at = "mapping.devices[" + std::to_string(n) + "]";
    const YAML::Node d = devices[n];
    DeviceMatch match;
    match.id = f.text(d, "id", at);
    for (const DeviceMatch& other : m.devices)
      if (other.id == match.id) f.fail(d["id"], at + ".id", "'" + match.id + "' is declared twice");
    match.keyboard = f.flag(d, "keyboard", at, false);
    match.mouse = f.flag(d, "mouse", at, false);
    if (match.keyboard && match.mouse) f.fail(d, at, "a device is the keyboard or the mouse, not both");
    if (f.optional(d, "guid", at)) {
      match.guid = f.text(d, "guid", at);
      if (match.guid.size() != 32 ||
          match.guid.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
        f.fail(d["guid"], at + ".guid", "an SDL GUID is 32 hexadecimal digits");
    }
    if (f.optional(d, "name", at)) match.name = f.text(d, "name", at);
    match.nth = f.optional(d, "nth", at) ? f.integer(d, "nth", at, 0, 15) : 0;
    if (!match.window_device() && match.guid.empty() && match.name.empty())
      f.fail(d, at, "a device is matched by guid, name or both (or is keyboard: true or mouse: true)");
    m.devices.push_back(match);
  }
  const YAML::Node bindings = f.sequence(root, "bindings", "mapping", 128);
  for (std::size_t n = 0; n < bindings.size(); ++n) {
    const YAML::Node e = bindings[n];
    const std::string at = "mapping.bindings[" + std::to_string(n) + "]";
    if (!e.IsMap()) f.fail(e, at, "expected a mapping (control, device, axis/button/hat/keys, ...)");
    Binding b;
    b.line = e.Mark().line + 1;
    b.control = f.text(e, "control", at);
    b.slot = table.find(b.control);
    if (b.slot < 0) {
      std::string known;
      for (const sim::ControlSpec& c : table.controls())
        known += (known.empty() ? "" : ", ") + c.label;
      f.fail(e["control"], at + ".control",
             "the machine has no control '" + b.control + "' (it has: " + known + ")");
    }
    const sim::ControlSpec& spec = table[b.slot];
    const std::string device = f.text(e, "device", at);
    const auto d = std::find_if(m.devices.begin(), m.devices.end(),
                                [&](const DeviceMatch& x) { return x.id == device; });
    if (d == m.devices.end())
      f.fail(e["device"], at + ".device", "no device '" + device + "' in mapping.devices");
    b.device = static_cast<int>(d - m.devices.begin());
    const bool axis = f.optional(e, "axis", at).has_value(), button = f.optional(e, "button", at).has_value(),
               hat = f.optional(e, "hat", at).has_value(), keys = f.optional(e, "keys", at).has_value(),
               key = f.optional(e, "key", at).has_value();
    if (axis + button + hat + keys + key != 1)
      f.fail(e, at, "binds exactly one of axis, button, hat, key or keys");
    if (d->keyboard != (keys || key))
      f.fail(e, at, d->keyboard ? "the keyboard binds key or keys" : "key and keys bind only the keyboard");
    if (d->mouse && (hat || (axis && f.integer(e, "axis", at, 0, 255) > 1) ||
                     (button && f.integer(e, "button", at, 0, 255) > 2)))
      f.fail(e, at, "the mouse has axes 0 (x) and 1 (y) and buttons 0 (left), 1 (middle), 2 (right)");
    if (axis) {
      b.source = Binding::Source::kAxis;
      b.index = static_cast<int>(f.integer(e, "axis", at, 0, 255));
      b.calibration = read_calibration(f, e, at);
    } else if (button) {
      b.source = Binding::Source::kButton;
      b.index = f.integer(e, "button", at, 0, 255);
    } else if (hat) {
      b.source = Binding::Source::kHat;
      b.index = f.integer(e, "hat", at, 0, 15);
      b.hat_direction = hat_direction(f, e, at);
    } else if (key) {
      b.source = Binding::Source::kButton;
      b.index = scancode(f, e["key"], at + ".key");
    } else {
      b.source = Binding::Source::kKeys;
      const YAML::Node pair = f.sequence(e, "keys", at, 2);
      if (pair.size() != 2) f.fail(pair, at + ".keys", "a key pair: [increase, decrease]");
      b.keys = {scancode(f, pair[0], at + ".keys[0]"), scancode(f, pair[1], at + ".keys[1]")};
    }
    b.dead_zone = f.number_or(e, "dead_zone", at, 0.0, 0.0, 0.9);
    b.expo = f.number_or(e, "expo", at, 0.0, 0.0, 1.0);
    b.invert = f.flag(e, "invert", at, false);
    b.toggle = f.flag(e, "toggle", at, false);
    b.value = f.number_or(e, "value", at, 1.0, -1e6, 1e6);
    b.hold_s = f.number_or(e, "hold_s", at, 0.0, 0.0, 5.0);
    if (b.hold_s > 0.0 && axis)
      f.fail(e["hold_s"], at + ".hold_s", "a button, hat or key is held for hold_s; an axis reads at once");
    if (f.optional(e, "detents", at)) {
      const YAML::Node list = f.sequence(e, "detents", at, 16);
      if (spec.kind != sim::ControlKind::kSwitch || !axis)
        f.fail(list, at + ".detents",
               "detents turn an axis into a switch's positions; '" + b.control + "' is a " +
                   sim::to_string(spec.kind));
      if (list.size() != spec.positions.size())
        f.fail(
            list, at + ".detents",
            "one detent per position of '" + b.control + "' (" + std::to_string(spec.positions.size()) + ")");
      for (std::size_t k = 0; k < list.size(); ++k) {
        b.detents.push_back(f.number_at(list[k], at + ".detents[" + std::to_string(k) + "]"));
        if (k > 0 && b.detents[k] <= b.detents[k - 1]) f.fail(list[k], at + ".detents", "detents must rise");
      }
    }
    if (b.toggle && (spec.kind != sim::ControlKind::kSwitch || axis))
      f.fail(e["toggle"], at + ".toggle", "toggle makes a button step a switch's positions");
    if (spec.kind == sim::ControlKind::kSwitch && axis && b.detents.empty())
      f.fail(e, at, "an axis on switch '" + b.control + "' needs detents (one per position)");
    m.bindings.push_back(b);
  }
  f.check_unknown_keys();
  return m;
}

DeviceMapping load_device_mapping(const std::string& path, const sim::ControlTable& table) {
  return load_device_mapping(io::YamlFile::load(path), table);
}

std::string key_list(const DeviceMapping& m, const sim::ControlTable& table) {
  std::string out = m.name + "\n";
  for (const sim::ControlSpec& spec : table.controls()) {
    std::string how;
    for (const Binding& b : m.bindings) {
      if (b.control != spec.label) continue;
      const std::string& device = m.devices[static_cast<std::size_t>(b.device)].id;
      std::string one;
      switch (b.source) {
        case Binding::Source::kAxis:
          one = device + " axis " + std::to_string(b.index);
          break;
        case Binding::Source::kButton:
          one = m.devices[static_cast<std::size_t>(b.device)].keyboard
                    ? std::string(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.index)))
                    : device + " button " + std::to_string(b.index);
          break;
        case Binding::Source::kHat:
          one = device + " hat " + std::to_string(b.index);
          break;
        case Binding::Source::kKeys:
          one = std::string(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.keys[0]))) + " / " +
                SDL_GetScancodeName(static_cast<SDL_Scancode>(b.keys[1]));
          break;
      }
      if (b.hold_s > 0.0) {
        char held[32];
        std::snprintf(held, sizeof held, " held %.1f s", b.hold_s);
        one += held;
      }
      if (b.toggle) one += " (each press steps it)";
      how += (how.empty() ? "" : ", ") + one;
    }
    if (!how.empty()) out += spec.label + " (" + spec.meaning + "): " + how + "\n";
  }
  return out +
         "look round: keypad 4 6 8 2, or drag with the left mouse button; keypad 5 looks ahead again\n"
         "F1 this list   F11 full screen";
}

std::string device_mapping_text(const DeviceMapping& m) {
  std::ostringstream out;
  const auto num = [](double v) {  // the shortest text that reads back to the same double
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    return std::string(text, end);
  };
  const auto quoted = [](const std::string& s) {
    std::string q = "\"";
    for (const char c : s)
      q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
  };
  out << "# written by harboursim devices\nmapping:\n  name: " << quoted(m.name) << "\n  devices:\n";
  for (const DeviceMatch& d : m.devices) {
    out << "    - {id: " << d.id;
    if (d.keyboard) out << ", keyboard: true";
    if (d.mouse) out << ", mouse: true";
    if (!d.guid.empty()) out << ", guid: \"" << d.guid << "\"";
    if (!d.name.empty()) out << ", name: " << quoted(d.name);
    if (d.nth) out << ", nth: " << d.nth;
    out << "}\n";
  }
  out << "  bindings:\n";
  for (const Binding& b : m.bindings) {
    out << "    - {control: " << b.control
        << ", device: " << m.devices[static_cast<std::size_t>(b.device)].id;
    switch (b.source) {
      case Binding::Source::kAxis:
        out << ", axis: " << b.index << ", calibration: {min: " << num(b.calibration.min);
        if (b.calibration.centered) out << ", center: " << num(b.calibration.center);
        out << ", max: " << num(b.calibration.max) << "}";
        break;
      case Binding::Source::kButton:
        if (m.devices[static_cast<std::size_t>(b.device)].keyboard)
          out << ", key: " << quoted(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.index)));
        else
          out << ", button: " << b.index;
        break;
      case Binding::Source::kHat:
        out << ", hat: " << b.index << ", direction: "
            << (b.hat_direction == SDL_HAT_UP      ? "up"
                : b.hat_direction == SDL_HAT_RIGHT ? "right"
                : b.hat_direction == SDL_HAT_DOWN  ? "down"
                                                   : "left");
        break;
      case Binding::Source::kKeys:
        out << ", keys: [" << quoted(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.keys[0]))) << ", "
            << quoted(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.keys[1]))) << "]";
        break;
    }
    if (b.dead_zone != 0.0) out << ", dead_zone: " << num(b.dead_zone);
    if (b.expo != 0.0) out << ", expo: " << num(b.expo);
    if (b.invert) out << ", invert: true";
    if (b.toggle) out << ", toggle: true";
    if (b.value != 1.0) out << ", value: " << num(b.value);
    if (b.hold_s != 0.0) out << ", hold_s: " << num(b.hold_s);
    if (!b.detents.empty()) {
      out << ", detents: [";
      for (std::size_t k = 0; k < b.detents.size(); ++k)
        out << (k ? ", " : "") << b.detents[k];
      out << "]";
    }
    out << "}\n";
  }
  return out.str();
}

std::string why_mapping_does_not_fit(const std::string& path, const sim::ControlTable& table) {
  try {
    const io::YamlFile f = io::YamlFile::load(path);
    const YAML::Node bindings = f.root()["mapping"]["bindings"];
    if (!bindings.IsSequence()) return {};
    for (const YAML::Node& b : bindings)
      if (b.IsMap() && b["control"].IsScalar() && table.find(b["control"].Scalar()) < 0)
        return "no control '" + b["control"].Scalar() + "'";
  } catch (const std::exception&) {
    // a broken file: the loader names the line and field
  }
  return {};
}

}  // namespace harbour::station
