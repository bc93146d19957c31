#pragma once

#include <stdexcept>
#include <string>

namespace harbour::io {

/// A bad data file: the message names the file, the line and the field.
class DataError : public std::runtime_error {
 public:
  DataError(std::string file, int line, std::string field, const std::string& problem)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + field + ": " + problem),
        file_(std::move(file)),
        line_(line),
        field_(std::move(field)) {}

  const std::string& file() const { return file_; }
  /// 1-based line; 0 when the file could not be read at all.
  int line() const { return line_; }
  const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_;
  std::string field_;
};

}  // namespace harbour::io
