#pragma once

#include <string>
#include <vector>

#include "harbour/io/MachineFiles.h"
#include "harbour/machines/parts/Drive.h"
#include "harbour/machines/parts/SpreaderHoist.h"
#include "harbour/machines/parts/WheeledChassis.h"

/// The readers of the parts machines share (drives, spreader hoists, wheels and tyres), as their machine
/// files give them: each machine's own reader (its folder's Files.cpp) reads its file with them. Compiled
/// with the files' readers (harbour_io). Every failure is a DataError naming file, line and field.
namespace harbour::io {

/// A motor drive (`at`.drive); `turns`: a rotary axis without end switches (slewing), no positions read.
sim::DriveSettings read_drive(const YamlFile& f, const YAML::Node& parent, const std::string& at,
                              bool turns = false);
/// Fails unless the drive's force gives what it moves (`moved_kg`) the drive's acceleration.
void check_drive_moves(const YamlFile& f, const YAML::Node& parent, const std::string& at,
                       const sim::DriveSettings& drive, double moved_kg, const char* what);
/// A container spreader (machine.spreader).
sim::SpreaderSettings read_spreader(const YamlFile& f, const YAML::Node& m);
/// A container spreader on its hoist ropes under a trolley whose centre runs `rail_height_m` up: the limit
/// switches (machine.hoist), the spreader, its twistlocks and the reeving (over `bodies`, the headblock
/// last).
sim::SpreaderHoistSettings read_spreader_hoist(const YamlFile& f, const YAML::Node& m,
                                               const std::string& folder,
                                               const std::vector<std::string>& bodies, double rail_height_m);
/// A wheeled machine's or trailer's axles (`path`.axles).
std::vector<sim::AxleSettings> read_axles(const YamlFile& f, const YAML::Node& m, const std::string& path);
/// A tyre (`path`.tyre).
sim::TyreSettings read_tyre(const YamlFile& f, const YAML::Node& m, const std::string& path);
/// A driven and steered machine's wheels (machine.axles, tyre, drivetrain, brake_torque_per_wheel_nm,
/// parking_brake_torque_per_wheel_nm on the axles marked parking_brake, max_steer_deg).
sim::WheeledChassisSettings read_wheels(const YamlFile& f, const YAML::Node& m);

}  // namespace harbour::io
