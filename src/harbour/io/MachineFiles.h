#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "harbour/cable/Reeving.h"
#include "harbour/io/YamlFile.h"
#include "harbour/scene/Controls.h"
#include "harbour/scene/Snapshot.h"

/// What every machine file (data/machines/*.yaml) has, whatever its machine: its controls, cab, reevings and
/// sections beside `machine`, and its kind; each machine's own reader (its folder's Files.cpp) reads its file
/// with these and its parts' readers (machines/parts/PartFiles.h). Every failure is a DataError naming file,
/// line and field.
namespace harbour::io {

// physical ranges (docs/reliability.md): wide enough for any real quay crane, narrow enough that the
// multibody solver sees well-conditioned masses and forces
inline constexpr double kMaxForce_n = 1e8;  ///< [N] 10 000 t: above any crane drive or brake
inline constexpr double kRails_m = 2000.0;  ///< [m] a quay's rails and a trolley's girder lie within this

/// The operator's cab (machine.cab): where it sits (within `reach_m` of the frame it is given in), the eye
/// in it and the design line of sight.
struct CabFields {
  core::Vec3 position_m, eye_m;
  scene::CabSight sight;
};
CabFields read_cab(const YamlFile& f, const YAML::Node& machine, double reach_m);
/// Every control the machine reads is in its table, of its kind; a missing or mistyped one names the list.
void require_controls(const YamlFile& f, const YAML::Node& machine, const scene::ControlTable& table,
                      std::initializer_list<std::pair<const char*, scene::ControlKind>> needed);
/// A reeving file named by `map`.`key` (relative to `folder`) over exactly `bodies`, with `drums` drums.
cable::ReevingSettings read_reeving_file(const YamlFile& f, const YAML::Node& map, const std::string& key,
                                         const std::string& at, const std::string& folder,
                                         const std::vector<std::string>& bodies, int drums);
/// A wheeled machine's chassis body (machine.chassis): its mass and its box about its centre of mass.
std::pair<double, core::Vec3> read_chassis_box(const YamlFile& f, const YAML::Node& m, double min_kg,
                                               double max_kg);
/// A vehicle's driving controls: steering wheel, pedals, the direction selector (reverse, neutral,
/// forward), the parking brake (released, set), emergency stop and horn.
void require_driving_controls(const YamlFile& f, const YAML::Node& m, const scene::ControlTable& controls);

/// The sections every machine file may have beside `machine`: its motion cues (`motion_cues`, checked here),
/// its looks (`looks`, read by the image generator) and its sounds (`sounds`, read by the station's sound). A
/// machine's reader calls it before check_unknown_keys.
void check_machine_file_sections(const YamlFile& f);

/// The kind a machine file declares (`machine.kind`, one of the registered machine types); throws DataError
/// naming the field.
std::string machine_file_kind(const std::string& path);
/// The controls a machine file declares (`machine.controls`, of a registered kind), as a device mapping binds
/// them; throws DataError naming the field.
scene::ControlTable machine_file_controls(const std::string& path);

}  // namespace harbour::io
