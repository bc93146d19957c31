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

/// Reads the washout settings of `machine` from a washout file (data/motion/washout.yaml): the file's
/// defaults overridden by the machine's section.
motion::WashoutSettings load_washout(const YamlFile& file, const std::string& machine);
motion::WashoutSettings load_washout(const std::string& path, const std::string& machine);

}  // namespace harbour::io
