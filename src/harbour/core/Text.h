#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace harbour::core {

/// Longest name or id a data file, the command line or the records accept [bytes].
inline constexpr std::size_t kMaxNameBytes = 256;

/// Why `text` cannot be a name ("" when it can): empty, longer than `max_bytes`, not valid UTF-8, or holding
/// a control character (NUL, newline, escape, DEL, C1). Names are printed to terminals and stored in
/// databases, so they carry no hidden characters.
std::string why_bad_name(std::string_view text, std::size_t max_bytes = kMaxNameBytes);

/// `text` safe to print: control characters and bytes that are not UTF-8 become \xHH escapes, and at most
/// `max_bytes` of it are shown (then "...").
std::string printable(std::string_view text, std::size_t max_bytes = kMaxNameBytes);

/// The items in one line, separated by ", " (a list in a message: "gust, hoist_brake_fault").
std::string comma_separated(const std::vector<std::string>& items);

/// This host's name ("" where it has none): what a station, a channel or the records say runs where.
std::string host_name();

}  // namespace harbour::core
