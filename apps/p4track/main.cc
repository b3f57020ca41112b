// p4track: the P4 table-tennis ball tracker, one program with subcommands (DESIGN.md).
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "p4/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"P4: real-time 3D table-tennis ball tracking, scoring and replay"};
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "More log output");
  const auto simulate = p4::app::AddSimulateCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info);
  spdlog::set_pattern("%^[%l]%$ %v");
  try {
    if (app.got_subcommand("simulate")) return simulate();
  } catch (const p4::Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("unexpected error: {}", e.what());
    return 3;
  }
  return 1;
}
