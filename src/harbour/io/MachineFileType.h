#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harbour/io/YamlFile.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::io {

/// The harbour an exercise takes place in: positions within 2 km of the crane's origin [m].
inline constexpr double kSite_m = 2000.0;

/// A figure of the machine's start pose an exercise gives under exercise.crane (a crane) or exercise.vehicle,
/// with the range its machine file allows; an optional one means `fallback` when left out.
struct StartPoseField {
  std::string key;
  int component = -1;  ///< position_m is three fields, components 0-2; -1: a number
  double min = 0.0, max = 0.0;
  bool exclusive_min = false;
  bool optional = false;
  double fallback = 0.0;
};
struct StartPoseForm {
  std::string section;  ///< "crane" or "vehicle"
  std::vector<StartPoseField> fields;
};
StartPoseField pose_number_field(const char* key, double min, double max);
StartPoseField pose_optional_field(const char* key, double fallback, double min, double max);
/// A form that starts with position_m on the site: a machine that stands anywhere on the quay.
StartPoseForm pose_on_the_quay(const char* section);

/// An exercise's start block (exercise.crane or exercise.vehicle) as a machine's reader sees it.
struct StartBlock {
  const YamlFile& file;  ///< the exercise file
  YAML::Node node;
  std::string at;      ///< its field path ("exercise.crane")
  std::string folder;  ///< the exercise file's folder: files the block names are relative to it

  /// position_m: the ground under the machine, on the site [m].
  core::Vec3 position() const;
  /// A number of the start pose, in the range `form` gives it (its fallback where optional and left out).
  double number(const StartPoseForm& form, const std::string& key) const;
};

/// How a kind of machine is read from files: its machine file with an exercise's start block, and the start
/// block's form (one table for the loader and the designer). Each machine folder defines its own
/// (`src/harbour/machines/<kind>/Files.cpp`, `<kind>_machine_files()`); the list of them is generated from
/// the folders when the build is configured, so a new machine's files are read without an edit here.
struct MachineFileType {
  const char* kind = "";                ///< as machine files name it (`machine.kind`)
  const char* start_section = "crane";  ///< the exercise's start block: "crane" or "vehicle"
  /// The machine file at `machine_path` and the exercise's start block; throws DataError naming the field.
  sim::MachineSetup (*read)(const std::string& machine_path, const StartBlock& start) = nullptr;
  /// The start block the loader reads for this setup (its machine file loaded).
  StartPoseForm (*start_pose_form)(const sim::MachineSetup& setup) = nullptr;
};

/// A MachineFileType's start_pose_form for a folder whose form is `Form(const Setup&)`.
template <typename Setup, StartPoseForm (*Form)(const Setup&)>
StartPoseForm start_pose_form_of(const sim::MachineSetup& setup) {
  return Form(setup.template as<Setup>());
}

/// Every machine kind's file reader (generated from the machine folders).
std::span<const MachineFileType* const> machine_file_types();
/// The reader of that kind, nullptr where there is none.
const MachineFileType* find_machine_file_type(std::string_view kind);

}  // namespace harbour::io
