#include "harbour/io/BoundedFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace harbour::io {

std::optional<std::string> read_bounded_file(const std::string& path, std::size_t max_bytes,
                                             std::string& why) {
  // O_NONBLOCK: opening a FIFO with no writer must not wait; the fstat below then refuses it
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    why = std::string("cannot be opened (") + std::strerror(errno) + ")";
    return std::nullopt;
  }
  struct ::stat st {};
  std::optional<std::string> out;
  if (::fstat(fd, &st) != 0) {
    why = std::string("cannot be read (") + std::strerror(errno) + ")";
  } else if (S_ISDIR(st.st_mode)) {
    why = "is a folder, not a file";
  } else if (!S_ISREG(st.st_mode)) {
    why = "is not a regular file (a FIFO, socket or device)";
  } else if (static_cast<unsigned long long>(st.st_size) > max_bytes) {
    why = "is " + std::to_string(st.st_size) + " bytes, over the limit of " + std::to_string(max_bytes);
  } else {
    // room for the size fstat gave, and one byte more to notice a file that grew since
    std::string bytes;
    bytes.resize(static_cast<std::size_t>(st.st_size) + 1);
    std::size_t have = 0;
    while (have < bytes.size()) {
      const ::ssize_t n = ::read(fd, bytes.data() + have, bytes.size() - have);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        why = std::string("cannot be read (") + std::strerror(errno) + ")";
        break;
      }
      if (n == 0) break;
      have += static_cast<std::size_t>(n);
    }
    if (why.empty() && have > static_cast<std::size_t>(st.st_size))
      why = "grew while it was read (still being written?)";
    if (why.empty()) {
      bytes.resize(have);
      out = std::move(bytes);
    }
  }
  ::close(fd);
  return out;
}

std::string why_not_writable(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) return "no file named";
  std::error_code ec;
  const fs::path p(path);
  const fs::file_status status = fs::status(p, ec);
  if (fs::exists(status)) {
    if (fs::is_directory(status)) return "is a folder";
    if (!fs::is_regular_file(status)) return "is not a regular file (a FIFO, socket or device)";
  }
  const fs::path folder = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, ec)) return "its folder " + folder.string() + " does not exist";
  if (::access(folder.c_str(), W_OK) != 0) return "its folder " + folder.string() + " is not writable";
  return {};
}

}  // namespace harbour::io
