#pragma once

#include <string>

namespace harbour::apps {

/// Options of the headless bulk demo.
struct BulkDemoOptions {
  std::string data_dir = "data";
  std::string out_dir = "out";
  int cycles = 6;  ///< grab cycles to run
};

/// Runs the demo: a grab digs from a yard heap and unloads into a rolling hold; prints progress and a
/// summary, writes out_dir/bulk_demo.png. Returns a process exit code.
int run_bulk_demo(const BulkDemoOptions& options);

}  // namespace harbour::apps
