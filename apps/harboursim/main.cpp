#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "BulkDemo.h"
#include "StsRun.h"

int main(int argc, char** argv) {
  CLI::App app{"harboursim: harbour crane training simulator"};
  app.require_subcommand(1);

  harbour::apps::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "run an exercise headless");
  run_cmd->add_option("--exercise", run.exercise, "exercise file (data/exercises/*.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  run_cmd->add_flag("--autopilot", run.autopilot, "let the scripted operator drive");
  run_cmd->add_option("--record", run.record, "write the run's recording (HSRC) to this file");

  std::string recording, replay_exercise;
  CLI::App* replay_cmd = app.add_subcommand("replay", "re-simulate a recording and check it bit for bit");
  replay_cmd->add_option("recording", recording, "recording file")->required()->check(CLI::ExistingFile);
  replay_cmd->add_option("--exercise", replay_exercise, "the exercise it was recorded on")
      ->required()
      ->check(CLI::ExistingFile);

  harbour::apps::BulkDemoOptions demo;
  CLI::App* demo_cmd =
      app.add_subcommand("bulk-demo", "a grab digs coal from a yard heap into a rolling hold");
  demo_cmd->add_option("--data", demo.data_dir, "data folder");
  demo_cmd->add_option("--out", demo.out_dir, "output folder");
  demo_cmd->add_option("--cycles", demo.cycles, "grab cycles")->check(CLI::PositiveNumber);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*run_cmd) return harbour::apps::run_exercise(run);
    if (*replay_cmd) return harbour::apps::replay_recording(recording, replay_exercise);
    return harbour::apps::run_bulk_demo(demo);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "harboursim: %s\n", e.what());
    return 1;
  }
}
