#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace harbour::io {

/// The bytes of `path` if it is a regular file of at most `max_bytes`; otherwise nullopt and `why` says what
/// it is instead (missing, a directory, a FIFO or device, too large, unreadable). Never blocks on a FIFO and
/// never reads more than `max_bytes` + 1 bytes, so a device or a growing file cannot exhaust memory.
std::optional<std::string> read_bounded_file(const std::string& path, std::size_t max_bytes,
                                             std::string& why);

/// "" when `path` can be created or overwritten as a regular file (its folder exists, it is not a folder or a
/// device), else why not. Checked before a run, so that a bad output path never costs a whole exercise.
std::string why_not_writable(const std::string& path);

}  // namespace harbour::io
