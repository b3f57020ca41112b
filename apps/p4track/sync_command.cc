// p4track sync: the cameras' clocks from the ball's own motion (cameras out of step: webcams and
// phones that started recording at their own moments), written into the rig.
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/io/color_class_file.h"
#include "p4/io/rig_file.h"
#include "p4/io/video_reader.h"
#include "p4/pipeline/ball_candidates.h"
#include "p4/segment/colour_learning.h"

namespace p4::app {
namespace {

struct SyncArgs {
  std::string rig, out, classes, ball = "any", streaks = "auto";
  std::vector<std::string> sources;
  double max_offset = 5.0, seconds = 0.0;
  bool rolling_shutter = false;
};

int Run(const SyncArgs& a) {
  const auto started = std::chrono::steady_clock::now();
  const Rig rig = ReadRig(a.rig);
  if (rig.size() < 2) throw Error(a.rig + ": one camera has nothing to be synchronised with");
  for (const auto& s : a.sources) {
    if (VideoReader::IsLive(s))
      throw Error(s + ": sync reads recordings (files), not live sources");
    if (!std::filesystem::exists(s)) throw Error(s + ": no such file");
  }
  const SyncBall ball = SyncBallOf(
      a.classes.empty() ? std::nullopt : std::optional(ReadColorClassFile(a.classes)), a.ball);
  const segment::ColorClassSet& classes = ball.classes;
  BallCandidateOptions candidates;
  // Enough play to cover the largest offset and then some.
  candidates.seconds = a.seconds > 0.0 ? a.seconds : std::max(15.0, 2.0 * a.max_offset + 5.0);
  candidates.ball = ball.streak;
  candidates.streak_max_fps = StreakMaxFps(a.streaks, candidates.streak_max_fps);
  sync::RigSyncOptions options;
  options.offsets.max_offset_s = a.max_offset;
  options.offsets.fit_line_times = a.rolling_shutter;
  spdlog::info("finding the clocks of {} camera(s) from the ball in the first {:.0f} s of {}",
               rig.size(), candidates.seconds,
               a.sources.size() == 1 ? "the source" : "each source");
  const sync::RigSyncResult result = SyncFromSources(rig, a.sources, classes, candidates, options);
  for (int c = 0; c < rig.size(); ++c) {
    const std::string line = DescribeClock(result.rig.cameras[c], result.cameras[c], c == 0);
    if (result.cameras[c].found) {
      spdlog::info("{} [{} 2D track(s)]", line, result.tracks[c]);
    } else {
      spdlog::error("{} [{} 2D track(s)]", line, result.tracks[c]);
    }
  }
  if (!result.all_found) {
    throw Error("sync: not every camera's clock was found (above); nothing written");
  }
  const std::string out = a.out.empty() ? a.rig : a.out;
  WriteRig(result.rig, out);
  spdlog::info("wrote the clocks into {} in {:.1f} s; `p4track track --rig {}` uses them", out,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
               out);
  return 0;
}

}  // namespace

std::function<int()> AddSyncCommand(CLI::App& app) {
  auto args = std::make_shared<SyncArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sync",
      "Find the cameras' time offsets (and drift) from the ball's motion and write them into the "
      "rig (cameras out of step: webcams, phones)");
  cmd->add_option("sources", args->sources, "One video file per camera, in the rig's order")
      ->required();
  cmd->add_option("--rig", args->rig, "Rig file; its first camera is the reference clock")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Write the rig with its clocks here (default: into --rig)");
  cmd->add_option("--classes", args->classes, "Colour classes file of the ball (YAML)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--ball", args->ball,
                  "The ball's colour when no --classes; any: whatever moves and is of its size")
      ->check(CLI::IsMember({"orange", "yellow", "white", "any"}))
      ->capture_default_str();
  cmd->add_option("--max-offset", args->max_offset, "Search offsets up to +- this many seconds")
      ->check(CLI::Range(0.05, 60.0))
      ->capture_default_str();
  cmd->add_option("--seconds", args->seconds,
                  "Read this much of each recording (default: 2 x --max-offset + 5 s, at least 15)")
      ->check(CLI::Range(0.0, 3600.0));
  cmd->add_option("--streaks", args->streaks,
                  "Faint blur streaks as the ball's views too: auto (cameras of 40 fps or slower, "
                  "whose long exposures leave a fast ball no sharp region), on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  cmd->add_flag("--rolling-shutter", args->rolling_shutter,
                "The cameras read their rows out one after another (phones, most webcams): find "
                "each camera's line time from the ball too (added to the rig's line_time_s)");
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
