#pragma once

#include <stdexcept>
#include <string>

#include "harbour/sim/Recording.h"

namespace harbour::io {

/// A recording file that cannot be read: names the file and the byte offset.
class RecordingFileError : public std::runtime_error {
 public:
  RecordingFileError(const std::string& file, std::size_t offset, const std::string& problem)
      : std::runtime_error(file + ": byte " + std::to_string(offset) + ": " + problem) {}
};

/// Version of the recording format written by this build ("HSRC" files).
/// 5 added a checksum to every keyframe; 4 added the instructor's commands; 3 the boom lever, horn, flipper
/// and spreader-size controls; 2 keyframes. Versions 1-4 are still read (the keyframes of 2 and 3 hold an
/// older machine state: a seek from one is refused with core::StateError).
inline constexpr std::uint16_t kRecordingVersion = 5;

/// Writes a recording (little-endian, magic "HSRC", kRecordingVersion; see docs/architecture.md) to a
/// temporary file and renames it over `path`, so a crash never leaves a half-written recording.
void write_recording(const std::string& path, const sim::Recording& recording);
/// Reads a recording; throws RecordingFileError (naming the file and byte) for a wrong magic, an unknown
/// version, truncated data, records out of order, values out of range or a damaged keyframe.
sim::Recording read_recording(const std::string& path);

}  // namespace harbour::io
