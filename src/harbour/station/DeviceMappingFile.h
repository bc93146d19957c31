#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/station/DeviceMapping.h"

namespace harbour::station {

/// Reads a device mapping file (data/devices/*.yaml) against a machine's control table: every binding's
/// control must be one of its labels and fit its kind. Errors (io::DataError) name file, line and field.
DeviceMapping load_device_mapping(const io::YamlFile& file, const scene::ControlTable& table);
DeviceMapping load_device_mapping(const std::string& path, const scene::ControlTable& table);
/// Why the mapping at `path` is for another machine: the first control it binds that `table` lacks ("" when
/// it binds only the machine's controls, or when the file is broken: load_device_mapping says how).
std::string why_mapping_does_not_fit(const std::string& path, const scene::ControlTable& table);

/// What a mapping's devices are, as a profile picks mappings by them: the keyboard or the mouse (a window's
/// devices), game pads through SDL's game controller API, or joysticks and levers matched by name or GUID.
enum class DeviceClass { kSticks, kGamePads, kKeyboards };
/// The class of the mapping at `path`: kKeyboards when any of its devices is the keyboard or the mouse, else
/// kGamePads when any is a game controller, else kSticks. Throws io::DataError naming a file that is no
/// mapping.
DeviceClass device_class_of(const std::string& path);
/// "sticks", "game_pads", "keyboards"
const char* to_string(DeviceClass c);

/// Why `line` is not one line of SDL's game controller mapping format ("GUID,name,a:b0,leftx:a0,...", as
/// in gamecontrollerdb.txt), naming the field; "" when it is.
std::string why_bad_controller_mapping(const std::string& line);
/// Whether a mapping line is for this platform (no "platform:" field, or SDL's own).
bool for_this_platform(const std::string& line);

/// The mapping as a file load_device_mapping reads back (what `harboursim devices` writes).
std::string device_mapping_text(const DeviceMapping& mapping);
/// What each control of the machine is worked by in `mapping`, a line each, for the trainee (the F1 list):
/// "hoist (hoist, + raises): W / S", "emergency_stop (...): Space held 0.5 s"; the station's own keys last.
std::string key_list(const DeviceMapping& mapping, const scene::ControlTable& table);

}  // namespace harbour::station
