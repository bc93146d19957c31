#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/motion/MotionSystem.h"
#include "harbour/motion/PlatformSequencer.h"

namespace harbour::io {

/// A motion platform file (data/motion/platform.yaml): geometry, limits and sequencer timing.
struct PlatformFile {
  std::string name;
  motion::StewartGeometry geometry;
  motion::MotionLimits limits;
  motion::SequencerSettings sequencer;
};

/// Reads a platform file; rejects geometry whose actuators cannot reach the neutral or parked pose.
PlatformFile load_platform(const YamlFile& file);
PlatformFile load_platform(const std::string& path);

/// The platform's washout for a machine: the washout file's (data/motion/washout.yaml) rate and defaults,
/// overridden channel by channel by the machine file's `motion_cues` (a tractor is cued harder than an STS).
motion::WashoutSettings load_washout(const YamlFile& washout_file, const YamlFile& machine_file);
motion::WashoutSettings load_washout(const std::string& washout_path, const std::string& machine_path);
/// Reads a machine file's `motion_cues` (absent: none) and fails naming a bad one: each machine's loader
/// calls it, so that the file's every key is read where the machine is.
void check_motion_cues(const YamlFile& machine_file);

}  // namespace harbour::io
