#pragma once

#include <string>

namespace harbour::station {

/// `harboursim devices`: list, watch, bind and calibrate input devices, write a mapping file.
struct DevicesOptions {
  bool watch = false;
  std::string bind;     ///< write a mapping file here, walking through the machine's controls
  std::string machine;  ///< the machine file whose controls are bound
  std::string name = "My desk";
  std::string virtual_device;  ///< NAME:AXES:BUTTONS:HATS: a virtual joystick (tests; no /dev/uinput here)
  int virtual_port = 0;  ///< UDP port moving the virtual joystick: "axis I V", "button I 0|1", "hat I BITS"
};
int run_devices(const DevicesOptions& options);

}  // namespace harbour::station
