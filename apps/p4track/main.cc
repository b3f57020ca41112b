// p4track: the P4 table-tennis ball tracker, one program with subcommands (DESIGN.md).
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <utility>
#include <vector>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/io/video_reader.h"

namespace {

int Run(int argc, char** argv) {
  CLI::App app{"P4: real-time 3D table-tennis ball tracking, scoring and replay"};
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "More log output");
  const std::vector<std::pair<std::string, std::function<int()>>> commands = {
      {"simulate", p4::app::AddSimulateCommand(app)},
      {"track", p4::app::AddTrackCommand(app)},
      {"eval", p4::app::AddEvalCommand(app)},
      {"calibrate", p4::app::AddCalibrateCommand(app)},
      {"replay", p4::app::AddReplayCommand(app)},
      {"bench", p4::app::AddBenchCommand(app)},
      {"eval-suite", p4::app::AddEvalSuiteCommand(app)},
      {"sync", p4::app::AddSyncCommand(app)},
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info);
  spdlog::set_pattern("%^[%l]%$ %v");
  p4::ShowFfmpegMessages(verbose);
  try {
    for (const auto& [name, run] : commands) {
      if (app.got_subcommand(name)) return run();
    }
  } catch (const p4::Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "p4track: unexpected error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "p4track: unexpected error\n");
  }
  return 3;
}
