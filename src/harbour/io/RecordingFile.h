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
/// 3 added the boom lever, horn, flipper and spreader-size controls; 2 added keyframes; 1 and 2 are still
/// read (their keyframes hold an older machine state: a seek from one is refused with core::StateError)
inline constexpr std::uint16_t kRecordingVersion = 4;

/// Writes a recording (little-endian, magic "HSRC", version 1; see docs/architecture.md) to a temporary file
/// and renames it over `path`, so a crash never leaves a half-written recording.
void write_recording(const std::string& path, const sim::Recording& recording);
/// Reads a recording; throws RecordingFileError for a wrong magic, an unknown version or truncated data.
sim::Recording read_recording(const std::string& path);

}  // namespace harbour::io
