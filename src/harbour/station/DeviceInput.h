#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "harbour/station/DeviceMapping.h"

struct _SDL_Joystick;
struct _SDL_GameController;

namespace harbour::station {

/// Something that happened to an input device, for the trainee's display, the instructor and the records.
struct DeviceEvent {
  enum class Kind : std::uint8_t {
    kConnected,  ///< a mapping device found (again)
    kLost,       ///< gone: its controls read safe until it comes back
    kUnfit,      ///< found but it lacks an axis, button or hat the mapping binds (detail says which)
  };
  Kind kind = Kind::kConnected;
  std::string device;  ///< the mapping's id (left, right, pad)
  std::string name;    ///< the SDL device's name
  std::string detail;  ///< the controls affected, or why it does not fit
};

/// Starts SDL's joystick and game controller subsystems the station's way (reference counted: pair with
/// quit_sdl_joysticks()); throws naming SDL's error. SDL reads its game controller database then, with
/// SDL_GAMECONTROLLERCONFIG and SDL_GAMECONTROLLERCONFIG_FILE from the environment. Hot-plug is watched
/// through inotify on /dev/input rather than a udev poll() in every SDL_JoystickUpdate: the step thread's
/// sample costs 2.2 us instead of 4.7 (bench_station). SDL_JOYSTICK_DISABLE_UDEV=0 in the environment keeps
/// udev.
void init_sdl_joysticks();
void quit_sdl_joysticks();

/// A joystick SDL sees now.
struct DeviceInfo {
  int instance = -1;
  std::string name, guid;
  int axes = 0, buttons = 0, hats = 0;
  std::string controller;  ///< its name as a game controller ("" where SDL has no mapping for it)
  std::string mapping;     ///< SDL's mapping of it ("" where it has none)
};

/// The station's input sensorisation over SDL2: any number of joysticks and game controllers, hot-plugged.
/// Devices are bound to a mapping's devices by GUID and/or name; sample() reads them and maps them to
/// Controls (fast, no allocation: the real-time loop calls it right before it latches, so a device change
/// reaches the very next step); maintain() finds, binds and drops devices (the input thread calls it).
/// A device that disappears makes its controls read safe in the same sample and raises an event; one that
/// comes back is bound again.
class DeviceInput {
 public:
  /// Initialises SDL's joystick subsystem and gives it the mapping's controller mappings (throws naming SDL's
  /// error and the mapping's line).
  DeviceInput(const scene::ControlTable& table, DeviceMapping mapping);
  ~DeviceInput();
  DeviceInput(const DeviceInput&) = delete;
  DeviceInput& operator=(const DeviceInput&) = delete;

  /// Reads the bound devices and maps them (any thread; one at a time).
  scene::Controls sample();
  /// A key went down (SDL's scancode, from the window's events): the next sample reads it pressed even if it
  /// is up again by then. SDL's keyboard state changes only as the window's thread pumps its events, so a tap
  /// whose press and release come in one pump would otherwise never be seen (a toggle's press lost).
  void key_went_down(int scancode);
  /// Finds new devices, binds them, drops lost ones (the station calls it 50 times a second).
  void maintain();

  /// Events since the last call.
  std::vector<DeviceEvent> take_events();
  /// Mapping devices that are bound now / missing now.
  int bound_devices() const;
  int missing_devices() const;
  /// What SDL sees (for `harboursim devices`).
  static std::vector<DeviceInfo> list();
  /// The mapping it reads the devices by.
  const DeviceMapping& mapping() const { return mapper_.mapping(); }
  /// Whether every joystick `mapping` names is present now (the keyboard counts as present only where
  /// there is a window: `keyboard`). SDL's joystick subsystem must be initialised.
  static bool all_present(const DeviceMapping& mapping, bool keyboard);

 private:
  struct Bound {
    _SDL_Joystick* joystick = nullptr;          // the device (a game controller's own joystick)
    _SDL_GameController* controller = nullptr;  // where the mapping reads it as a game controller
    int instance = -1;
    std::string name;
  };
  static void close(const Bound& bound);
  void drop(std::size_t device, bool lost);
  void event(DeviceEvent e);

  ControlMapper mapper_;
  mutable std::mutex mutex_;         // the bound devices: sample() and maintain()
  std::vector<Bound> bound_;         // per mapping device
  std::vector<DeviceState> states_;  // per mapping device
  std::vector<std::string> unfit_;   // per mapping device: the last unfit reason reported
  struct Used {
    std::vector<int> axes, buttons, hats;  // what the mapping binds: only these are read
  };
  std::vector<Used> used_;  // per mapping device
  std::vector<bool> keyboard_;
  std::mutex keys_mutex_;             // key_went_down() from the window's thread
  std::vector<bool> keys_went_down_;  // by scancode, since the last sample
  scene::Controls last_;
  std::mutex events_mutex_;
  std::vector<DeviceEvent> events_;
};

}  // namespace harbour::station
