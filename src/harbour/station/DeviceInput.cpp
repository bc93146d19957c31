#include "harbour/station/DeviceInput.h"

#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/station/DeviceMappingFile.h"

namespace harbour::station {

namespace {
std::string guid_of(SDL_JoystickGUID guid) {
  char text[33];
  SDL_JoystickGetGUIDString(guid, text, sizeof text);
  return text;
}

/// Whether SDL's device `index` is what `m` means: a game controller by its name as one, a joystick by its.
bool matches(const DeviceMatch& m, int index) {
  if (m.window_device()) return false;
  if (m.game_controller && !SDL_IsGameController(index)) return false;
  const char* raw =
      m.game_controller ? SDL_GameControllerNameForIndex(index) : SDL_JoystickNameForIndex(index);
  const std::string name = raw ? raw : "";
  if (!m.guid.empty() &&
      SDL_strcasecmp(m.guid.c_str(), guid_of(SDL_JoystickGetDeviceGUID(index)).c_str()) != 0)
    return false;
  if (!m.name.empty() && name.find(m.name) == std::string::npos) return false;
  return true;
}

/// Why a game controller lacks an axis or button mapping device `device` binds ("" when it has them all).
std::string why_controller_unfit(const DeviceMapping& mapping, int device, SDL_GameController* c) {
  for (const Binding& b : mapping.bindings) {
    if (b.device != device) continue;
    const bool has = b.source == Binding::Source::kAxis
                         ? SDL_GameControllerHasAxis(c, static_cast<SDL_GameControllerAxis>(b.index))
                         : SDL_GameControllerHasButton(c, static_cast<SDL_GameControllerButton>(b.index));
    if (!has)
      return mapping.file + ":" + std::to_string(b.line) + ": bindings." + b.control + ": '" +
             (b.source == Binding::Source::kAxis
                  ? SDL_GameControllerGetStringForAxis(static_cast<SDL_GameControllerAxis>(b.index))
                  : SDL_GameControllerGetStringForButton(static_cast<SDL_GameControllerButton>(b.index))) +
             "' is not in SDL's mapping of this controller";
  }
  return {};
}

}  // namespace

void init_sdl_joysticks() {
  SDL_SetHint(SDL_HINT_JOYSTICK_ALLOW_BACKGROUND_EVENTS, "1");
  setenv("SDL_JOYSTICK_DISABLE_UDEV", "1", 0);
  if (SDL_InitSubSystem(SDL_INIT_GAMECONTROLLER) != 0)
    throw std::runtime_error(std::string("SDL joystick subsystem: ") + SDL_GetError());
}

void quit_sdl_joysticks() {
  SDL_QuitSubSystem(SDL_INIT_GAMECONTROLLER);  // and its joysticks
}

DeviceInput::DeviceInput(const scene::ControlTable& table, DeviceMapping mapping)
    : mapper_(table, std::move(mapping)) {
  init_sdl_joysticks();
  for (const ControllerMapping& m : mapper_.mapping().controller_mappings)
    if (for_this_platform(m.text) && SDL_GameControllerAddMapping(m.text.c_str()) < 0) {
      const std::string why = SDL_GetError();
      quit_sdl_joysticks();
      throw std::runtime_error(m.where + ": controller_mappings: SDL refuses it: " + why);
    }
  const std::size_t devices = mapper_.mapping().devices.size();
  bound_.resize(devices);
  states_.resize(devices);
  unfit_.resize(devices);
  used_.resize(devices);
  for (std::size_t d = 0; d < devices; ++d)
    if (mapper_.mapping().devices[d].mouse) states_[d] = {false, {0.0, 0.0}, {false, false, false}, {}};
  for (const Binding& b : mapper_.mapping().bindings) {
    Used& u = used_[static_cast<std::size_t>(b.device)];
    std::vector<int>& list = b.source == Binding::Source::kAxis     ? u.axes
                             : b.source == Binding::Source::kButton ? u.buttons
                                                                    : u.hats;
    if (b.source != Binding::Source::kKeys && std::find(list.begin(), list.end(), b.index) == list.end())
      list.push_back(b.index);
  }
  last_ = mapper_.map(states_, keyboard_);
}

DeviceInput::~DeviceInput() {
  {
    const std::lock_guard lock(mutex_);
    for (std::size_t d = 0; d < bound_.size(); ++d)
      close(bound_[d]);
  }
  quit_sdl_joysticks();
}

std::vector<DeviceInfo> DeviceInput::list() {
  std::vector<DeviceInfo> out;
  SDL_JoystickUpdate();
  for (int i = 0; i < SDL_NumJoysticks(); ++i) {
    DeviceInfo info;
    info.instance = SDL_JoystickGetDeviceInstanceID(i);
    const char* name = SDL_JoystickNameForIndex(i);
    info.name = name ? name : "";
    info.guid = guid_of(SDL_JoystickGetDeviceGUID(i));
    if (SDL_Joystick* j = SDL_JoystickOpen(i)) {
      info.axes = SDL_JoystickNumAxes(j);
      info.buttons = SDL_JoystickNumButtons(j);
      info.hats = SDL_JoystickNumHats(j);
      SDL_JoystickClose(j);
    }
    if (SDL_IsGameController(i)) {
      const char* controller = SDL_GameControllerNameForIndex(i);
      info.controller = controller ? controller : "";
      if (char* mapping = SDL_GameControllerMappingForDeviceIndex(i)) {
        info.mapping = mapping;
        SDL_free(mapping);
      }
    }
    out.push_back(info);
  }
  return out;
}

bool DeviceInput::all_present(const DeviceMapping& mapping, bool keyboard) {
  SDL_JoystickUpdate();
  for (const DeviceMatch& d : mapping.devices) {
    if (d.window_device()) {
      if (!keyboard) return false;
      continue;
    }
    int rank = 0;
    for (int i = 0; i < SDL_NumJoysticks(); ++i)
      rank += matches(d, i);
    if (rank <= d.nth) return false;
  }
  return true;
}

scene::Controls DeviceInput::sample() {
  const std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return last_;  // maintain() is binding a device: the previous sample, one step old
  SDL_JoystickUpdate();
  for (std::size_t d = 0; d < bound_.size(); ++d) {
    if (mapper_.mapping().devices[d].window_device()) continue;
    DeviceState& state = states_[d];
    SDL_Joystick* j = bound_[d].joystick;
    state.connected = j && SDL_JoystickGetAttached(j);
    if (!state.connected) continue;
    // only what the mapping binds (maintain() checked the device has them)
    const Used& u = used_[d];
    if (SDL_GameController* c = bound_[d].controller) {
      for (const int a : u.axes)
        state.axes[static_cast<std::size_t>(a)] =
            SDL_GameControllerGetAxis(c, static_cast<SDL_GameControllerAxis>(a));
      for (const int b : u.buttons)
        state.buttons[static_cast<std::size_t>(b)] =
            SDL_GameControllerGetButton(c, static_cast<SDL_GameControllerButton>(b)) != 0;
      continue;
    }
    for (const int a : u.axes)
      state.axes[static_cast<std::size_t>(a)] = SDL_JoystickGetAxis(j, a);
    for (const int b : u.buttons)
      state.buttons[static_cast<std::size_t>(b)] = SDL_JoystickGetButton(j, b) != 0;
    for (const int h : u.hats)
      state.hats[static_cast<std::size_t>(h)] = SDL_JoystickGetHat(j, h);
  }
  if (SDL_WasInit(SDL_INIT_VIDEO)) {
    // the mouse across the station's window, as a device of two axes from its centre and three buttons
    int x = 0, y = 0, w = 0, h = 0;
    const Uint32 buttons = SDL_GetMouseState(&x, &y);
    SDL_Window* window = SDL_GetMouseFocus();
    if (window) SDL_GetWindowSize(window, &w, &h);
    for (std::size_t d = 0; d < states_.size(); ++d) {
      if (!mapper_.mapping().devices[d].mouse) continue;
      DeviceState& m = states_[d];
      m.connected = window && w > 0 && h > 0;
      const auto raw = [](double n) { return n >= 0.0 ? n * 32767.0 : n * 32768.0; };  // a joystick's range
      m.axes = {m.connected ? raw(2.0 * x / w - 1.0) : 0.0, m.connected ? raw(2.0 * y / h - 1.0) : 0.0};
      m.buttons = {(buttons & SDL_BUTTON_LMASK) != 0, (buttons & SDL_BUTTON_MMASK) != 0,
                   (buttons & SDL_BUTTON_RMASK) != 0};
    }
    int keys = 0;
    const Uint8* pressed = SDL_GetKeyboardState(&keys);
    keyboard_.resize(static_cast<std::size_t>(keys));
    for (int k = 0; k < keys; ++k)
      keyboard_[static_cast<std::size_t>(k)] = pressed[k] != 0;
    const std::lock_guard keys_lock(keys_mutex_);
    for (std::size_t k = 0; k < keys_went_down_.size() && k < keyboard_.size(); ++k) {
      if (keys_went_down_[k]) keyboard_[k] = true;
      keys_went_down_[k] = false;
    }
  }
  last_ =
      mapper_.map(states_, keyboard_,
                  std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count());
  return last_;
}

void DeviceInput::key_went_down(int scancode) {
  if (scancode <= 0 || scancode >= SDL_NUM_SCANCODES) return;
  const std::lock_guard lock(keys_mutex_);
  keys_went_down_.resize(SDL_NUM_SCANCODES, false);
  keys_went_down_[static_cast<std::size_t>(scancode)] = true;
}

void DeviceInput::event(DeviceEvent e) {
  const std::lock_guard lock(events_mutex_);
  events_.push_back(std::move(e));
}

void DeviceInput::close(const Bound& b) {
  if (b.controller)
    SDL_GameControllerClose(b.controller);  // and its joystick
  else if (b.joystick)
    SDL_JoystickClose(b.joystick);
}

void DeviceInput::drop(std::size_t d, bool lost) {
  close(bound_[d]);
  if (lost)
    event({DeviceEvent::Kind::kLost, mapper_.mapping().devices[d].id, bound_[d].name,
           "safe: " + core::comma_separated(mapper_.controls_of(static_cast<int>(d)))});
  bound_[d] = {};
  states_[d].connected = false;
}

void DeviceInput::maintain() {
  const std::lock_guard lock(mutex_);
  SDL_JoystickUpdate();
  // lost devices first: their slots free for a device that comes back
  for (std::size_t d = 0; d < bound_.size(); ++d)
    if (bound_[d].joystick && !SDL_JoystickGetAttached(bound_[d].joystick)) drop(d, true);
  const DeviceMapping& mapping = mapper_.mapping();
  const int count = SDL_NumJoysticks();
  for (std::size_t d = 0; d < mapping.devices.size(); ++d) {
    if (bound_[d].joystick || mapping.devices[d].window_device()) continue;
    // the nth joystick that matches this mapping device (in SDL's device order)
    int rank = 0, index = -1;
    for (int i = 0; i < count && index < 0; ++i)
      if (matches(mapping.devices[d], i) && rank++ == mapping.devices[d].nth) index = i;
    if (index < 0) continue;
    const SDL_JoystickID instance = SDL_JoystickGetDeviceInstanceID(index);
    bool taken = false;
    for (const Bound& b : bound_)
      taken = taken || b.instance == instance;
    if (taken) continue;
    Bound bound{nullptr, nullptr, instance, ""};
    int axes = 0, buttons = 0, hats = 0;
    std::string why;
    if (mapping.devices[d].game_controller) {
      bound.controller = SDL_GameControllerOpen(index);
      if (!bound.controller) continue;
      bound.joystick = SDL_GameControllerGetJoystick(bound.controller);
      const char* n = SDL_GameControllerName(bound.controller);
      bound.name = n ? n : "";
      axes = SDL_CONTROLLER_AXIS_MAX;
      buttons = SDL_CONTROLLER_BUTTON_MAX;
      why = why_controller_unfit(mapping, static_cast<int>(d), bound.controller);
    } else {
      bound.joystick = SDL_JoystickOpen(index);
      if (!bound.joystick) continue;
      const char* n = SDL_JoystickName(bound.joystick);
      bound.name = n ? n : "";
      axes = SDL_JoystickNumAxes(bound.joystick);
      buttons = SDL_JoystickNumButtons(bound.joystick);
      hats = SDL_JoystickNumHats(bound.joystick);
      why = why_unfit(mapping, static_cast<int>(d), axes, buttons, hats);
    }
    if (!why.empty()) {
      close(bound);
      if (unfit_[d] != why) event({DeviceEvent::Kind::kUnfit, mapping.devices[d].id, bound.name, why});
      unfit_[d] = why;
      continue;
    }
    unfit_[d].clear();
    const std::string name = bound.name;
    bound_[d] = std::move(bound);
    states_[d].axes.assign(static_cast<std::size_t>(axes), 0.0);
    states_[d].buttons.assign(static_cast<std::size_t>(buttons), false);
    states_[d].hats.assign(static_cast<std::size_t>(hats), 0);
    event({DeviceEvent::Kind::kConnected, mapping.devices[d].id, name,
           core::comma_separated(mapper_.controls_of(static_cast<int>(d)))});
  }
}

std::vector<DeviceEvent> DeviceInput::take_events() {
  const std::lock_guard lock(events_mutex_);
  std::vector<DeviceEvent> out;
  out.swap(events_);
  return out;
}

int DeviceInput::bound_devices() const {
  const std::lock_guard lock(mutex_);
  int n = 0;
  for (const Bound& b : bound_)
    n += b.joystick != nullptr;
  return n;
}

int DeviceInput::missing_devices() const {
  const std::lock_guard lock(mutex_);
  int n = 0;
  for (std::size_t d = 0; d < bound_.size(); ++d)
    n += !mapper_.mapping().devices[d].window_device() && bound_[d].joystick == nullptr;
  return n;
}

}  // namespace harbour::station
