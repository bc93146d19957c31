#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "BulkDemo.h"

namespace {

int usage() {
  std::fprintf(stderr,
               "usage: harboursim bulk-demo [--data DIR] [--out DIR] [--cycles N]\n"
               "  bulk-demo   a grab digs coal from a yard heap into a rolling hold (headless)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "bulk-demo";
  if (command != "bulk-demo") return usage();
  harbour::apps::BulkDemoOptions options;
  for (int n = 2; n < argc; ++n) {
    const std::string arg = argv[n];
    if (n + 1 >= argc) return usage();
    const std::string value = argv[++n];
    if (arg == "--data")
      options.data_dir = value;
    else if (arg == "--out")
      options.out_dir = value;
    else if (arg == "--cycles") {
      options.cycles = std::atoi(value.c_str());
      if (options.cycles < 1) return usage();
    } else
      return usage();
  }
  try {
    return harbour::apps::run_bulk_demo(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "harboursim: %s\n", e.what());
    return 1;
  }
}
