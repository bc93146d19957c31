#include "harbour/station/DeviceMappingFile.h"

#include <SDL.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "harbour/io/BoundedFile.h"

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

/// SDL's name of a game controller axis or button ("leftx", "a", "dpup"), or -1.
int controller_axis(const std::string& name) {
  for (int a = 0; a < SDL_CONTROLLER_AXIS_MAX; ++a)
    if (name == SDL_GameControllerGetStringForAxis(static_cast<SDL_GameControllerAxis>(a))) return a;
  return -1;
}
int controller_button(const std::string& name) {
  for (int b = 0; b < SDL_CONTROLLER_BUTTON_MAX; ++b)
    if (name == SDL_GameControllerGetStringForButton(static_cast<SDL_GameControllerButton>(b))) return b;
  return -1;
}
std::string controller_names(bool axes) {
  std::string names;
  const int count =
      axes ? static_cast<int>(SDL_CONTROLLER_AXIS_MAX) : static_cast<int>(SDL_CONTROLLER_BUTTON_MAX);
  for (int k = 0; k < count; ++k)
    names += std::string(names.empty() ? "" : ", ") +
             (axes ? SDL_GameControllerGetStringForAxis(static_cast<SDL_GameControllerAxis>(k))
                   : SDL_GameControllerGetStringForButton(static_cast<SDL_GameControllerButton>(k)));
  return names;
}

/// A game controller's axis or button by SDL's name (a raw index means nothing on a pad SDL maps).
int controller_input(const io::YamlFile& f, const YAML::Node& entry, const std::string& key,
                     const std::string& at) {
  const YAML::Node node = entry[key];
  const int index = node.IsScalar()
                        ? (key == "axis" ? controller_axis(node.Scalar()) : controller_button(node.Scalar()))
                        : -1;
  if (index < 0)
    f.fail(node, at + "." + key,
           "a game controller's " + key + " is named as SDL names it: " + controller_names(key == "axis"));
  return index;
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

/// A pad's input in a trainee's words: "left stick up/down", "A", "d-pad up", "right trigger".
std::string pad_input_words(const Binding& b) {
  if (b.source == Binding::Source::kAxis) {
    switch (b.index) {
      case SDL_CONTROLLER_AXIS_LEFTX:
        return "left stick left/right";
      case SDL_CONTROLLER_AXIS_LEFTY:
        return "left stick up/down";
      case SDL_CONTROLLER_AXIS_RIGHTX:
        return "right stick left/right";
      case SDL_CONTROLLER_AXIS_RIGHTY:
        return "right stick up/down";
      case SDL_CONTROLLER_AXIS_TRIGGERLEFT:
        return "left trigger";
      default:
        return "right trigger";
    }
  }
  switch (b.index) {
    case SDL_CONTROLLER_BUTTON_A:
      return "A";
    case SDL_CONTROLLER_BUTTON_B:
      return "B";
    case SDL_CONTROLLER_BUTTON_X:
      return "X";
    case SDL_CONTROLLER_BUTTON_Y:
      return "Y";
    case SDL_CONTROLLER_BUTTON_BACK:
      return "Back";
    case SDL_CONTROLLER_BUTTON_GUIDE:
      return "Guide";
    case SDL_CONTROLLER_BUTTON_START:
      return "Start";
    case SDL_CONTROLLER_BUTTON_LEFTSTICK:
      return "left stick press";
    case SDL_CONTROLLER_BUTTON_RIGHTSTICK:
      return "right stick press";
    case SDL_CONTROLLER_BUTTON_LEFTSHOULDER:
      return "left bumper";
    case SDL_CONTROLLER_BUTTON_RIGHTSHOULDER:
      return "right bumper";
    case SDL_CONTROLLER_BUTTON_DPAD_UP:
      return "d-pad up";
    case SDL_CONTROLLER_BUTTON_DPAD_DOWN:
      return "d-pad down";
    case SDL_CONTROLLER_BUTTON_DPAD_LEFT:
      return "d-pad left";
    case SDL_CONTROLLER_BUTTON_DPAD_RIGHT:
      return "d-pad right";
    default:
      return SDL_GameControllerGetStringForButton(static_cast<SDL_GameControllerButton>(b.index));
  }
}

// one binding: a control of the machine's table to an input of one of the mapping's devices
Binding read_binding(const io::YamlFile& f, const YAML::Node& e, const std::string& at,
                     const scene::ControlTable& table, const DeviceMapping& m) {
  if (!e.IsMap()) f.fail(e, at, "expected a mapping (control, device, axis/button/hat/keys, ...)");
  Binding b;
  b.line = e.Mark().line + 1;
  b.control = f.text(e, "control", at);
  b.slot = table.find(b.control);
  if (b.slot < 0) {
    std::string known;
    for (const scene::ControlSpec& c : table.controls())
      known += (known.empty() ? "" : ", ") + c.label;
    f.fail(e["control"], at + ".control",
           "the machine has no control '" + b.control + "' (it has: " + known + ")");
  }
  const scene::ControlSpec& spec = table[b.slot];
  const std::string device = f.text(e, "device", at);
  const auto d =
      std::find_if(m.devices.begin(), m.devices.end(), [&](const DeviceMatch& x) { return x.id == device; });
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
  if (d->game_controller && hat)
    f.fail(e["hat"], at + ".hat", "a game controller's d-pad is buttons: dpup, dpright, dpdown, dpleft");
  if (axis) {
    b.source = Binding::Source::kAxis;
    b.index = d->game_controller ? controller_input(f, e, "axis", at)
                                 : static_cast<int>(f.integer(e, "axis", at, 0, 255));
    b.calibration = read_calibration(f, e, at);
    if (d->game_controller && !f.optional(e, "calibration", at) &&
        (b.index == SDL_CONTROLLER_AXIS_TRIGGERLEFT || b.index == SDL_CONTROLLER_AXIS_TRIGGERRIGHT))
      b.calibration = {0.0, 0.0, 32767.0, false};  // SDL reads a trigger 0 (released) to 32767
  } else if (button) {
    b.source = Binding::Source::kButton;
    b.index = d->game_controller ? controller_input(f, e, "button", at) : f.integer(e, "button", at, 0, 255);
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
    if (spec.kind != scene::ControlKind::kSwitch || !axis)
      f.fail(list, at + ".detents",
             "detents turn an axis into a switch's positions; '" + b.control + "' is a " +
                 scene::to_string(spec.kind));
    if (list.size() != spec.positions.size())
      f.fail(
          list, at + ".detents",
          "one detent per position of '" + b.control + "' (" + std::to_string(spec.positions.size()) + ")");
    for (std::size_t k = 0; k < list.size(); ++k) {
      b.detents.push_back(f.number_at(list[k], at + ".detents[" + std::to_string(k) + "]"));
      if (k > 0 && b.detents[k] <= b.detents[k - 1]) f.fail(list[k], at + ".detents", "detents must rise");
    }
  }
  if (b.toggle && (spec.kind != scene::ControlKind::kSwitch || axis))
    f.fail(e["toggle"], at + ".toggle", "toggle makes a button step a switch's positions");
  if (spec.kind == scene::ControlKind::kSwitch && axis && b.detents.empty())
    f.fail(e, at, "an axis on switch '" + b.control + "' needs detents (one per position)");
  return b;
}

}  // namespace

DeviceMapping load_device_mapping(const io::YamlFile& f, const scene::ControlTable& table) {
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
    match.game_controller = f.flag(d, "game_controller", at, false);
    if (match.game_controller && match.window_device())
      f.fail(d, at, "a game controller is neither the keyboard nor the mouse");
    if (f.optional(d, "name", at)) match.name = f.text(d, "name", at);
    match.nth = f.optional(d, "nth", at) ? f.integer(d, "nth", at, 0, 15) : 0;
    if (!match.window_device() && !match.game_controller && match.guid.empty() && match.name.empty())
      f.fail(d, at,
             "a device is matched by guid, name or both (or is keyboard: true, mouse: true or "
             "game_controller: true)");
    m.devices.push_back(match);
  }
  const YAML::Node bindings = f.sequence(root, "bindings", "mapping", 128);
  for (std::size_t n = 0; n < bindings.size(); ++n) {
    const std::string at = "mapping.bindings[" + std::to_string(n) + "]";
    m.bindings.push_back(read_binding(f, bindings[n], at, table, m));
  }
  if (f.optional(root, "controller_mappings", "mapping")) {
    const YAML::Node list = f.sequence(root, "controller_mappings", "mapping", 64);
    for (std::size_t n = 0; n < list.size(); ++n) {
      const std::string at = "mapping.controller_mappings[" + std::to_string(n) + "]";
      if (!list[n].IsScalar()) f.fail(list[n], at, "expected one line of SDL's mapping format");
      if (const std::string why = why_bad_controller_mapping(list[n].Scalar()); !why.empty())
        f.fail(list[n], at, why);
      m.controller_mappings.push_back(
          {list[n].Scalar(), f.name() + ":" + std::to_string(list[n].Mark().line + 1)});
    }
  }
  if (f.optional(root, "controller_db", "mapping")) {
    // a gamecontrollerdb.txt, relative to the mapping file
    std::filesystem::path path = f.text(root, "controller_db", "mapping");
    if (path.is_relative()) path = std::filesystem::path(f.name()).parent_path() / path;
    std::string why;
    const auto text = io::read_bounded_file(path.string(), 4u << 20, why);
    if (!text) f.fail(root["controller_db"], "mapping.controller_db", path.string() + ": " + why);
    std::istringstream lines(*text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty() || line[0] == '#') continue;
      if (!for_this_platform(line)) continue;
      if (const std::string bad = why_bad_controller_mapping(line); !bad.empty())
        throw io::DataError(path.string(), number, "controller mapping", bad);
      m.controller_mappings.push_back({line, path.string() + ":" + std::to_string(number)});
    }
  }
  f.check_unknown_keys();
  return m;
}

bool for_this_platform(const std::string& line) {
  const std::size_t at = line.find(",platform:");
  if (at == std::string::npos) return true;
  const std::size_t start = at + 10;
  return line.compare(start, line.find(',', start) - start, SDL_GetPlatform()) == 0;
}

std::string why_bad_controller_mapping(const std::string& line) {
  // GUID,name,field:value,... (SDL's gamecontrollerdb.txt): the GUID, a name, then inputs SDL knows
  const std::size_t first = line.find(','),
                    second = first == std::string::npos ? first : line.find(',', first + 1);
  if (second == std::string::npos) return "an SDL mapping is 'GUID,name,a:b0,leftx:a0,...'";
  const std::string guid = line.substr(0, first);
  if (guid != "xinput" &&
      (guid.size() != 32 || guid.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos))
    return "'" + guid + "' is not an SDL GUID (32 hexadecimal digits)";
  if (second == first + 1) return "the mapping has no name";
  std::istringstream fields(line.substr(second + 1));
  std::string field;
  int inputs = 0;
  while (std::getline(fields, field, ',')) {
    if (field.empty()) continue;
    const std::size_t colon = field.find(':');
    if (colon == std::string::npos) return "field '" + field + "' is not name:value";
    std::string key = field.substr(0, colon);
    const std::string value = field.substr(colon + 1);
    if (key == "platform" || key == "crc" || key == "hint" || key == "sdk>=" || key == "sdk<=") continue;
    if (!key.empty() && (key[0] == '+' || key[0] == '-')) key.erase(0, 1);  // half an axis
    if (controller_axis(key) < 0 && controller_button(key) < 0)
      return "'" + key + "' is not an input SDL knows (axes: " + controller_names(true) +
             "; buttons: " + controller_names(false) + ")";
    // b3, h0.4, a2, +a2, -a2, a2~ (inverted)
    std::size_t k = 0;
    if (k < value.size() && (value[k] == '+' || value[k] == '-')) ++k;
    const char kind = k < value.size() ? value[k] : 0;
    std::size_t digits = ++k;
    while (k < value.size() && std::isdigit(static_cast<unsigned char>(value[k])))
      ++k;
    bool fits = (kind == 'a' || kind == 'b' || kind == 'h') && k > digits;
    if (fits && kind == 'h') {
      fits = k < value.size() && value[k] == '.';
      digits = ++k;
      while (k < value.size() && std::isdigit(static_cast<unsigned char>(value[k])))
        ++k;
      fits = fits && k > digits;
    }
    if (fits && kind == 'a' && k < value.size() && value[k] == '~') ++k;
    if (!fits || k != value.size())
      return "'" + field + "': an input is b<button>, h<hat>.<mask> or a<axis> (+/- half, ~ inverted)";
    ++inputs;
  }
  if (inputs == 0) return "the mapping maps no input";
  return {};
}

DeviceMapping load_device_mapping(const std::string& path, const scene::ControlTable& table) {
  return load_device_mapping(io::YamlFile::load(path), table);
}

std::string key_list(const DeviceMapping& m, const scene::ControlTable& table) {
  std::string out = m.name + "\n";
  for (const scene::ControlSpec& spec : table.controls()) {
    std::string how;
    for (const Binding& b : m.bindings) {
      if (b.control != spec.label) continue;
      const DeviceMatch& match = m.devices[static_cast<std::size_t>(b.device)];
      const std::string& device = match.id;
      std::string one;
      switch (b.source) {
        case Binding::Source::kAxis:
          one = match.game_controller ? device + " " + pad_input_words(b)
                                      : device + " axis " + std::to_string(b.index);
          break;
        case Binding::Source::kButton:
          one = match.keyboard          ? std::string(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.index)))
                : match.game_controller ? device + " " + pad_input_words(b)
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
    if (d.game_controller) out << ", game_controller: true";
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
        if (m.devices[static_cast<std::size_t>(b.device)].game_controller)
          out << ", axis: "
              << SDL_GameControllerGetStringForAxis(static_cast<SDL_GameControllerAxis>(b.index));
        else
          out << ", axis: " << b.index;
        out << ", calibration: {min: " << num(b.calibration.min);
        if (b.calibration.centered) out << ", center: " << num(b.calibration.center);
        out << ", max: " << num(b.calibration.max) << "}";
        break;
      case Binding::Source::kButton:
        if (m.devices[static_cast<std::size_t>(b.device)].keyboard)
          out << ", key: " << quoted(SDL_GetScancodeName(static_cast<SDL_Scancode>(b.index)));
        else if (m.devices[static_cast<std::size_t>(b.device)].game_controller)
          out << ", button: "
              << SDL_GameControllerGetStringForButton(static_cast<SDL_GameControllerButton>(b.index));
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
  if (!m.controller_mappings.empty()) {
    out << "  controller_mappings:\n";
    for (const ControllerMapping& c : m.controller_mappings)
      out << "    - " << quoted(c.text) << "\n";
  }
  return out.str();
}

DeviceClass device_class_of(const std::string& path) {
  const io::YamlFile f = io::YamlFile::load(path);
  const YAML::Node root = f.required_map(f.root(), "mapping", "");
  const YAML::Node devices = f.sequence(root, "devices", "mapping", 16);
  bool window = false, pad = false;
  for (std::size_t n = 0; n < devices.size(); ++n) {
    const std::string at = "mapping.devices[" + std::to_string(n) + "]";
    window = f.flag(devices[n], "keyboard", at, false) || f.flag(devices[n], "mouse", at, false) || window;
    pad = f.flag(devices[n], "game_controller", at, false) || pad;
  }
  return window ? DeviceClass::kKeyboards : pad ? DeviceClass::kGamePads : DeviceClass::kSticks;
}

const char* to_string(DeviceClass c) {
  switch (c) {
    case DeviceClass::kSticks:
      return "sticks";
    case DeviceClass::kGamePads:
      return "game_pads";
    case DeviceClass::kKeyboards:
      return "keyboards";
  }
  return "?";
}

std::string why_mapping_does_not_fit(const std::string& path, const scene::ControlTable& table) {
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
