// p4track replay DIR: a recorded run in the browser — 3D replay at any speed from any viewpoint,
// the timeline of bounces, strokes and points, the score as it was, the bounce maps and each
// shot's speed. Read-only; served by P4 itself, offline.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <memory>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/server/web_server.h"
#include "web_ui.h"

namespace p4::app {
namespace {

struct ReplayArgs {
  std::string dir;
  WebFlags web;
};

int Run(const ReplayArgs& a) {
  namespace fs = std::filesystem;
  if (!fs::exists(fs::path(a.dir) / "trajectory.csv")) {
    throw Error(a.dir + ": no trajectory.csv (a folder written by `p4track track --out`)");
  }
  if (!fs::exists(fs::path(a.dir) / "events.jsonl")) {
    spdlog::warn("{}: no events.jsonl (tracked with --no-referee?): no timeline marks, no score",
                 a.dir);
  }
  server::WebServer web(a.web.Options());
  web.ServeRun(a.dir);
  StartAndAnnounce(&web, a.web, "replay of " + a.dir);
  spdlog::info("Ctrl-C to stop");
  WaitForInterrupt();
  return 0;
}

}  // namespace

std::function<int()> AddReplayCommand(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand(
      "replay", "Replay a tracked run in 3D in the browser (any speed, any viewpoint)");
  cmd->add_option("dir", args->dir, "Run folder written by `p4track track --out`")
      ->required()
      ->check(CLI::ExistingDirectory);
  args->web.Add(cmd);
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
