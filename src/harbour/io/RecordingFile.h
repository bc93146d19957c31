#pragma once

#include <cstdio>
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
/// 11 adds the name of a box handed onto this station's trailer (TeamInput::kLoadOn's item); 10 adds the
/// team obstacles (TeamInput::kObstacleAt, with its size: another member's machine body); 9 adds
/// team records (what a team session's other stations made happen: sim::TeamInput); 8 says in its
/// header's flags whether the run's hoist ropes started stretched under their load (bit 0; runs recorded
/// before started unstretched, and their replays start so); 6 streams tagged records (inputs, checkpoints,
/// keyframes, commands) as they happen and ends with an end record, so a killed run leaves a replayable
/// prefix; 5 added a checksum to every keyframe; 4 the instructor's commands; 3 the boom lever, horn, flipper
/// and spreader-size controls; 2 keyframes. Versions 1-5 are still read (the keyframes of 2 and 3 hold an
/// older machine state: a seek from one is refused with core::StateError).
inline constexpr std::uint16_t kRecordingVersion = 11;

/// Longest recording read [steps]: 24 hours at 1 kHz (docs/reliability.md).
inline constexpr std::int64_t kMaxRecordingSteps = 24LL * 3600 * 1000;
/// Largest recording file read [bytes].
inline constexpr std::size_t kMaxRecordingBytes = std::size_t{1} << 30;

/// Streams a recording to a file as it is made (a RecordingSink for sim::Recorder): the header and any prefix
/// at once, each record as it comes, flushed at every checkpoint (each simulated second). A run that is
/// killed leaves a file read_recording() reads as an incomplete recording up to its last checkpoint.
class RecordingWriter final : public sim::RecordingSink {
 public:
  /// Creates (or truncates) `path` and writes the header and everything `prefix` already holds; throws
  /// std::runtime_error naming the file when it cannot be written.
  RecordingWriter(const std::string& path, const sim::Recording& prefix);
  ~RecordingWriter() override;
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  void on_input(const sim::Recording::InputChange& change) override;
  void on_checkpoint(const sim::Recording::Checkpoint& checkpoint) override;
  void on_keyframe(const sim::Recording::Keyframe& keyframe) override;
  void on_command(const sim::Recording::Command& command) override;
  void on_team(const sim::Recording::TeamEvent& event) override;
  /// Writes the end record and closes the file: the recording is complete, `total_steps` long.
  void finish(std::int64_t total_steps);
  const std::string& path() const { return path_; }

 private:
  void write(const std::vector<unsigned char>& bytes, bool flush);
  std::string path_;
  scene::Controls last_input_;  // the last input change written (the next is stored as its difference)
  std::size_t control_count_ = 0;
  std::FILE* file_ = nullptr;
};

/// Writes a whole recording to `path` (through a RecordingWriter).
void write_recording(const std::string& path, const sim::Recording& recording);
/// Reads a recording (a regular file of at most kMaxRecordingBytes); throws RecordingFileError (naming the
/// file and byte) for a wrong magic, an unknown version, truncated data (except the torn last record of an
/// incomplete v6 recording), records out of order, values out of range, checkpoints that do not cover every
/// second of it, a branch step beyond it, or a damaged keyframe.
sim::Recording read_recording(const std::string& path);
/// The same from a recording file's bytes held elsewhere (the records database's copy); `name` names them in
/// errors.
sim::Recording parse_recording(const std::string& name, std::string bytes);
/// A finished recording file's bytes, to keep with its attempt in the records ("" where it is larger than
/// `most` bytes or cannot be read: the file stays the only copy).
std::string recording_copy(const std::string& path, std::size_t most);

}  // namespace harbour::io
