#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harbour/scene/Controls.h"

namespace harbour::station {

/// Which physical device a mapping means: by SDL GUID and/or by name (exact), the n-th of several alike.
struct DeviceMatch {
  std::string id;    ///< the mapping's name for it: left, right, pad, pedals, keyboard
  std::string guid;  ///< SDL GUID (32 hex characters), "" for any
  std::string
      name;     ///< a part of the SDL device name ("" for any): "T.16000M" matches "Thrustmaster T.16000M"
  int nth = 0;  ///< 0: the first device that matches, 1: the second, ...
  bool keyboard = false;  ///< the keyboard: present where the station has a window
  bool mouse = false;     ///< the mouse in the station's window: axes 0 (x) and 1 (y) across the window from
                          ///< its centre, buttons 0 left, 1 middle, 2 right
  /// read through SDL's GameController API: any pad SDL has a mapping for (its own database, the
  /// mapping's controller_mappings, SDL_GAMECONTROLLERCONFIG), axes and buttons by SDL's names
  /// (Binding::index is an SDL_GameControllerAxis or SDL_GameControllerButton)
  bool game_controller = false;
  bool window_device() const { return keyboard || mouse; }
};

/// Two-sided (min, centre, max) or one-sided (min, max: a pedal or throttle) raw axis calibration.
struct Calibration {
  double min = -32768.0, center = 0.0, max = 32767.0;
  bool centered = true;
};

/// One physical control bound to one control label.
struct Binding {
  enum class Source : std::uint8_t { kAxis, kButton, kHat, kKeys };
  std::string control;  ///< label in the machine's control table
  int slot = -1;        ///< its slot (resolved against the table)
  int device = 0;       ///< index into DeviceMapping::devices
  Source source = Source::kAxis;
  int index = 0;                    ///< axis, button or hat index (kKeys: unused)
  int hat_direction = 0;            ///< SDL_HAT_UP/RIGHT/DOWN/LEFT bits for kHat
  std::array<int, 2> keys{-1, -1};  ///< kKeys: SDL scancodes for + and - (a key pair as a lever)
  Calibration calibration;
  double dead_zone = 0.0;  ///< [-] share of the travel around the centre (or the rest end) that reads 0
  double expo = 0.0;       ///< [-] response curve: (1 - e) x + e x^3
  bool invert = false;
  std::vector<double> detents;  ///< an axis driving a switch: the normalised positions of its detents
  bool toggle = false;          ///< a button driving a switch: each press moves it to the next position
  /// a button, hat or key on an axis control: the value while held; on a switch: the position it selects
  /// (the switch stays there when it is let go, as a selector does)
  double value = 1.0;
  /// [s] a button, hat or key counts only once held this long (a deliberate press: a tap of the space bar is
  /// no emergency stop)
  double hold_s = 0.0;
  int line = 0;  ///< where it is in its file (errors name it)
};

/// One line of SDL's game controller mapping format (gamecontrollerdb.txt): "GUID,name,a:b0,leftx:a0,...".
struct ControllerMapping {
  std::string text;
  std::string where;  ///< file and line it came from (errors name it)
};

/// A mapping file (data/devices/*.yaml): devices and their bindings to a machine's control labels.
struct DeviceMapping {
  std::string name;
  std::string file;  ///< where it was read from
  std::vector<DeviceMatch> devices;
  std::vector<Binding> bindings;
  /// game controller mappings SDL is given before the devices are looked for: pads its own database lacks
  std::vector<ControllerMapping> controller_mappings;
};

/// One device's raw state as SDL reports it (or a test sets it).
struct DeviceState {
  bool connected = false;
  std::vector<double> axes;  ///< raw -32768..32767
  std::vector<bool> buttons;
  std::vector<int> hats;  ///< SDL_HAT_* bits
};

/// Why mapping device `device` cannot be bound to a device with these counts ("" if it can): an axis, button
/// or hat index beyond it, named by file, line and field.
std::string why_unfit(const DeviceMapping& mapping, int device, int axes, int buttons, int hats);

/// The normalised reading of one axis binding: calibration, dead zone, expo and inversion, in [-1, 1]
/// (two-sided) or [0, 1] (one-sided).
double shape_axis(const Binding& binding, double raw);

/// Turns device states into Controls through a mapping: axes by their calibration and curve into the
/// control's range, buttons, hats and keys, detents and toggles for switches. A control bound to a device
/// that is not connected reads its safe value; the rest read neutral when untouched.
class ControlMapper {
 public:
  ControlMapper(const scene::ControlTable& table, DeviceMapping mapping);

  /// The controls for these device states (one per mapping device, in its order). `keyboard` holds the
  /// pressed scancodes' flags (SDL_NUM_SCANCODES entries, or empty when there is no keyboard).
  /// `now_s`: a steady clock's reading [s] (a binding's hold_s is timed by it).
  scene::Controls map(const std::vector<DeviceState>& devices, const std::vector<bool>& keyboard = {},
                      double now_s = 0.0);
  const DeviceMapping& mapping() const { return mapping_; }
  const scene::ControlTable& table() const { return table_; }
  /// Labels of the controls bound to mapping device `device`.
  std::vector<std::string> controls_of(int device) const;

 private:
  scene::ControlTable table_;
  DeviceMapping mapping_;
  std::vector<bool> was_pressed_;     // per binding: a toggle's previous button state
  std::vector<double> held_since_s_;  // per binding: since when it has been held (NaN: it is not)
  std::vector<double> toggled_;       // per slot: a switch's position as buttons last put it
};

}  // namespace harbour::station
