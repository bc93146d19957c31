#pragma once

// Bad-data checks shared by the loader tests: one edit to a good file, then the exact error expected.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "harbour/io/YamlFile.h"

namespace harbour::scenes {

/// The whole text of a (shipped) data file.
inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// 1-based line of the first occurrence of `needle` in `text`.
inline int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// Replaces `from` by `to` in `text`, loads the result as "bad.yaml" with `load(const io::YamlFile&)`, and
/// expects an io::DataError at `line` for `field` whose message contains `says`.
template <typename Load>
void expect_data_error(std::string text, const std::string& from, const std::string& to, Load load, int line,
                       const std::string& field, const std::string& says = "") {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  try {
    load(io::YamlFile::parse(text, "bad.yaml"));
    FAIL() << "accepted: " << to;
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.file(), "bad.yaml");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

}  // namespace harbour::scenes
