#pragma once
// harboursim started as a separate process, as a person or a centre starts it (the tests under tests/apps).

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace harbour::apps {

namespace fs = std::filesystem;

// an empty folder of that name under the temporary directory
inline fs::path fresh_folder(const std::string& name) {
  const fs::path folder = fs::temp_directory_path() / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// starts harboursim (HARBOUR_APP) with `arguments`, its output to `log`
inline pid_t start_app(const std::vector<std::string>& arguments, const fs::path& log) {
  const pid_t child = fork();
  if (child == 0) {
    freopen(log.c_str(), "w", stdout);
    freopen(log.c_str(), "a", stderr);
    std::vector<std::string> args = arguments;
    args.insert(args.begin(), HARBOUR_APP);
    std::vector<char*> argv;
    for (std::string& a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(HARBOUR_APP, argv.data());
    _exit(127);
  }
  return child;
}

// waits for `child` to end: its exit code, or minus the signal that ended it
inline int exit_code(pid_t child) {
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

}  // namespace harbour::apps
