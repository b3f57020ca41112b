// p4track track: the tracker over recorded or live sources (paper §3), writing the run's files.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/io/calib_files.h"
#include "p4/io/color_class_file.h"
#include "p4/io/event_files.h"
#include "p4/io/rig_file.h"
#include "p4/io/video_reader.h"
#include "p4/pipeline/ball_candidates.h"
#include "p4/pipeline/learn_colour.h"
#include "p4/pipeline/track_run.h"
#include "p4/segment/colour_learning.h"
#include "p4/server/live_hub.h"
#include "web_ui.h"

namespace p4::app {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(WebFlags, bind, port, web_dir)

namespace {

struct TrackArgs {
  std::string rig, out, classes, ball = "auto", filter = "p4";
  std::vector<std::string> sources;
  bool no_roi = false, no_single_camera = false, no_smoothing = false, no_confirm = false;
  bool no_flight_check = false;
  std::string detector = "auto", streaks = "auto";
  int stride = 1, threads = 1, candidates = 8;
  double epipolar_px = 4.0;
  std::vector<std::string> players{"A", "B"};
  std::string first_server = "A";
  int best_of = 5;
  bool no_referee = false;
  bool no_sync = false, rolling_shutter = false;
  double max_offset = 5.0;
  bool ui = false, realtime = false, loop = false;
  std::string layout;
  WebFlags web;
  std::string resume;  // a run folder to continue (its options from its run.json)
};

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(TrackArgs, rig, out, classes, ball, filter, sources,
                                                no_roi, no_single_camera, no_smoothing, no_confirm,
                                                detector, streaks, stride, threads, candidates,
                                                epipolar_px, players, first_server, best_of,
                                                no_referee, no_sync, rolling_shutter, max_offset,
                                                ui, realtime, loop, layout, web, no_flight_check)

// DIR/run.json: the run's options (paths made absolute, so that --resume works from anywhere) and
// whether it finished. Written when a run starts and when it ends (atomically).
void WriteRunJson(TrackArgs a, bool finished) {
  const auto absolute = [](std::string* path) {
    if (!path->empty() && !VideoReader::IsLive(*path)) {
      *path = std::filesystem::absolute(*path).lexically_normal().string();
    }
  };
  absolute(&a.rig);
  absolute(&a.classes);
  absolute(&a.layout);
  for (auto& source : a.sources) absolute(&source);
  const std::string out = a.out;
  absolute(&a.out);
  WriteJson((std::filesystem::path(out) / "run.json").string(),
            {{"command", "track"}, {"options", a}, {"finished", finished}});
}

// The options of the run in `dir` (its run.json), to make it again and continue it.
TrackArgs ResumedArgs(const std::string& dir, bool* finished) {
  const std::string path = (std::filesystem::path(dir) / "run.json").string();
  if (!std::filesystem::exists(path)) {
    throw Error(path +
                ": not found: --resume needs a folder that `p4track track` began (it saves "
                "its options there)");
  }
  nlohmann::json j;
  try {
    std::ifstream in(path);
    j = nlohmann::json::parse(in);
    TrackArgs a = j.at("options").get<TrackArgs>();
    *finished = j.value("finished", false);
    a.out = dir;
    return a;
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not a run's options: " + e.what());
  }
}

// Cameras whose clocks the rig does not give are synchronised from the ball before tracking
// (recordings of two or more cameras); the clocks found are saved as rig_synced.yaml in the run's
// folder. A rig that gives them, one camera, live sources or --no-sync: as the rig says.
Rig SyncIfNeeded(const TrackArgs& a, const std::optional<ColorClassFile>& file, Rig rig) {
  const bool unknown = std::any_of(rig.cameras.begin() + 1, rig.cameras.end(),
                                   [](const Camera& c) { return !c.clock.has_offset; });
  const bool live = std::any_of(a.sources.begin(), a.sources.end(), VideoReader::IsLive);
  if (a.no_sync || rig.size() < 2 || !unknown || live) return rig;
  const SyncBall ball = SyncBallOf(file, a.ball);
  const segment::ColorClassSet& classes = ball.classes;
  BallCandidateOptions candidates;
  candidates.seconds = std::max(15.0, 2.0 * a.max_offset + 5.0);
  candidates.ball = ball.streak;
  candidates.streak_max_fps = StreakMaxFps(a.streaks, candidates.streak_max_fps);
  sync::RigSyncOptions options;
  options.offsets.max_offset_s = a.max_offset;
  options.offsets.fit_line_times = a.rolling_shutter;
  spdlog::info(
      "{} gives no time offsets: finding them from the ball in the first {:.0f} s (--no-sync: "
      "take the cameras as in step)",
      a.rig, candidates.seconds);
  const sync::RigSyncResult found = SyncFromSources(rig, a.sources, classes, candidates, options);
  if (!found.all_found) {
    for (int c = 1; c < rig.size(); ++c) {
      if (!found.cameras[c].found) {
        spdlog::warn("{}", DescribeClock(rig.cameras[c], found.cameras[c], false));
      }
    }
    spdlog::warn("taking the cameras as in step (run `p4track sync` on a longer recording)");
    return rig;
  }
  for (int c = 1; c < rig.size(); ++c) {
    spdlog::info("{}", DescribeClock(found.rig.cameras[c], found.cameras[c], false));
  }
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) throw Error(a.out + ": cannot create the folder (" + ec.message() + ")");
  const std::string saved = (std::filesystem::path(a.out) / "rig_synced.yaml").string();
  WriteRig(found.rig, saved);
  spdlog::info("saved the rig with its clocks to {} (reuse with --rig: no search)", saved);
  return found.rig;
}

// Why a run with these options cannot be made again by --resume (empty: it can): only runs over
// files that did not loop can.
std::string WhyNotResumable(const TrackArgs& a) {
  for (const auto& s : a.sources) {
    if (VideoReader::IsLive(s)) {
      return "the run read " + s +
             ", a live source: only runs over files can be resumed (a live picture cannot be "
             "made again)";
    }
  }
  if (a.loop) return "the run played its files in a loop: it has no end to resume";
  return {};
}

int Run(TrackArgs a) {
  const bool resume = !a.resume.empty();
  if (resume) {
    bool finished = false;
    a = ResumedArgs(a.resume, &finished);
    if (finished) {
      spdlog::info("{}: the run finished; nothing to resume", a.out);
      return 0;
    }
    if (const std::string why = WhyNotResumable(a); !why.empty()) throw Error(a.out + ": " + why);
    a.realtime = a.ui = false;
    spdlog::info(
        "resuming {}: the run is made again from its start with its own options (run.json); "
        "what its files hold is checked and kept, the rest appended",
        a.out);
  } else if (a.rig.empty() || a.out.empty() || a.sources.empty()) {
    throw Error("track: --rig, --out and one source per camera are needed (or --resume DIR)");
  }
  for (const auto& s : a.sources) {
    if (!VideoReader::IsLive(s) && !std::filesystem::exists(s)) throw Error(s + ": no such file");
  }
  if (!a.layout.empty() && !a.ui)
    throw Error("--layout " + a.layout + ": shown by the live view only (add --ui)");
  if (!resume) {
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec) throw Error(a.out + ": cannot create the folder (" + ec.message() + ")");
    WriteRunJson(a, false);
  }
  Rig read_rig = ReadRig(a.rig);
  // --classes: its classes, and the ball's colour when a learning run saved the file.
  const std::optional<ColorClassFile> file =
      a.classes.empty() ? std::nullopt : std::optional(ReadColorClassFile(a.classes));
  const Rig rig = SyncIfNeeded(a, file, std::move(read_rig));
  bool learn = !file && a.ball == "auto";
  segment::ColorClassSet classes = file ? file->classes : segment::NamedBall(a.ball);
  // --ball auto learns from recordings with two or more cameras (views that agree across
  // cameras and fly are the ball); one camera's recordings choose among the named colours the
  // one that flies; live sources: the orange ball's classes (docs/DECISIONS.md).
  bool choose = false;
  if (learn) {
    const auto live = std::find_if(a.sources.begin(), a.sources.end(), VideoReader::IsLive);
    if (live != a.sources.end()) {
      spdlog::warn(
          "--ball auto learns the ball's colour from recordings; {} is live: tracking an orange "
          "ball (give --ball orange|white|yellow or --classes FILE, e.g. the ball_classes.yaml a "
          "run on a recording of this hall saved)",
          *live);
      learn = false;
    } else if (rig.size() < 2) {
      choose = true;
      learn = false;
    }
  }
  track::FrameSetOptions options;
  options.use_roi = !a.no_roi;
  options.confirm_tracks = !a.no_confirm;
  bool white = a.ball == "white";
  options.measure_on_background = a.detector == "coverage";
  options.mask_with_background = a.detector == "masked";
  options.segment.stride = a.stride;
  options.single_camera_fallback = !a.no_single_camera;
  options.epipolar_px = a.epipolar_px;
  options.threads = a.threads;
  options.candidates_per_camera = a.candidates;
  options.streaks = a.streaks == "on"    ? track::FrameSetOptions::Streaks::kOn
                    : a.streaks == "off" ? track::FrameSetOptions::Streaks::kOff
                                         : track::FrameSetOptions::Streaks::kAuto;
  segment::BallColour::Named(a.ball, &options.ball_colour);
  // A file a learning run saved gives the ball's colour as well: the run is the same again.
  if (file && file->ball) {
    options.ball_colour = *file->ball;
    white = file->ball->IsWhite();
  }
  // A learnt colour: the classes to track with, saved beside the run (reuse with --classes).
  // The folder first: a run that cannot save what it learns should not spend the time.
  if (choose || learn) {
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec) throw Error(a.out + ": cannot create the folder (" + ec.message() + ")");
  }
  const auto take_learnt = [&](const LearnColourResult& learnt) {
    classes = learnt.colour.classes;
    options.ball_colour = learnt.colour.ball;
    const std::string saved = (std::filesystem::path(a.out) / "ball_classes.yaml").string();
    WriteColorClasses(classes, saved, &learnt.colour.ball);
    return saved;
  };
  if (choose) {
    // Not white: the background model it needs takes whatever moves for the ball (an arm, a
    // shirt), which flies in one camera's view as often as the ball does.
    const std::vector<std::string> names{"orange", "yellow"};
    spdlog::info(
        "one camera: choosing the ball's colour among {} by what flies in the first 10 s (a "
        "second camera would let it be learnt)",
        fmt::join(names, ", "));
    const NamedColourChoice chosen = ChooseNamedColour(rig, a.sources, names, options);
    std::vector<std::string> counts;
    for (const auto& [name, views] : chosen.views) {
      counts.push_back(fmt::format("{} {}", name, views));
    }
    if (chosen.name.empty()) {
      spdlog::warn(
          "no ball of a named colour flew in the first {:.1f} s (views of confirmed flights: "
          "{}): tracking an orange ball (give --ball or --classes)",
          chosen.seconds, fmt::join(counts, ", "));
    } else {
      spdlog::info("tracking {} {} ball (views of confirmed flights in {:.1f} s: {})",
                   chosen.name == "orange" ? "an" : "a", chosen.name, chosen.seconds,
                   fmt::join(counts, ", "));
      classes = segment::NamedBall(chosen.name);
      segment::BallColour::Named(chosen.name, &options.ball_colour);
      white = chosen.name == "white";
      // Its shades in this hall, from its own flights (the named boxes may take only the lit
      // part of a ball in a dim hall); saved beside the run as a learning run's are.
      LearnColourOptions learning;
      learning.tracking = options;
      try {
        const LearnColourResult learnt = LearnNamedColour(rig, a.sources, chosen.name, learning);
        if (learnt.named_taken >= learning.keep_named_share) {
          spdlog::info("the {} ball's named colours take {:.1f} % of its pixels in this hall",
                       chosen.name, 100.0 * learnt.named_taken);
        } else {
          const std::string saved = take_learnt(learnt);
          const segment::Yuv& lit = learnt.colour.ball.lit;
          spdlog::info(
              "the {} ball's named colours take only {:.1f} % of its pixels in this hall: learnt "
              "its shades from {} views in {} tracks (lit YUV {:.0f} {:.0f} {:.0f}, {} classes), "
              "saved to {} (reuse with --classes)",
              chosen.name, 100.0 * learnt.named_taken, learnt.views, learnt.tracks, lit.y, lit.u,
              lit.v, classes.classes.size(), saved);
        }
      } catch (const Error& e) {
        spdlog::warn("{}; tracking with the {} ball's named colours", e.what(), chosen.name);
      }
    }
  }
  if (learn) {
    LearnColourOptions learning;
    learning.tracking = options;
    spdlog::info("learning the ball's colour from the sources' first {:.0f} s",
                 learning.max_seconds);
    try {
      const LearnColourResult learnt = LearnBallColour(rig, a.sources, learning);
      const std::string saved = take_learnt(learnt);
      white = learnt.colour.ball.IsWhite();
      const segment::Yuv& lit = learnt.colour.ball.lit;
      spdlog::info(
          "learnt the ball's colour from {} views in {} tracks ({:.1f} s): lit YUV {:.0f} {:.0f} "
          "{:.0f}{}, {} classes (they take {:.1f} % of the ball's pixels, {:.2f} % of the other "
          "moving pixels, {:.2f} % before giving up the colours those have more of), saved to {} "
          "(reuse with --classes)",
          learnt.views, learnt.tracks, learnt.seconds, lit.y, lit.u, lit.v,
          white ? " (a white ball)" : "", classes.classes.size(),
          100.0 * (1.0 - learnt.colour.ball_lost), 100.0 * learnt.colour.moving_taken,
          100.0 * learnt.colour.moving_taken_before, saved);
    } catch (const Error& e) {
      // A source that cannot be read fails again below, with its own message.
      spdlog::warn("{}; tracking an orange ball", e.what());
    }
  }
  // auto: the background detector for a white ball (colour alone cannot single it out among
  // lines, lamps and walls), the colour tables for the others (docs/DECISIONS.md, Detection).
  options.use_background = a.detector == "background" || (a.detector == "auto" && white);
  // The long-term background (a player who stood still and stepped away leaves no ghost to hide
  // the ball in) where the background is the detector. The colour tables' helpers (a floor of
  // the ball's colour split on the background, webcams' faint streaks) keep the short-term model
  // their thresholds were chosen with: with the long-term one, the players it brings back are
  // pieces of a ball-coloured floor's colour too (mono tuning 3: 15.9 -> 253 mm).
  options.background.long_term = options.use_background;
  if (a.filter == "paper") options.tracker.kalman.noise = track::KalmanOptions::Noise::kPaper;
  GameOptions game;
  game.enabled = !a.no_referee;
  game.referee.best_of = a.best_of;
  game.referee.first_server = a.first_server == "B" ? 'B' : 'A';
  game.players = {a.players[0], a.players[1]};
  // The live view: its own threads; the tracking loop only hands it each frame set.
  std::unique_ptr<server::LiveHub> hub;
  std::unique_ptr<server::WebServer> web;
  RunExtras extras;
  extras.realtime = a.realtime;
  extras.smooth_one_camera = !a.no_smoothing;
  extras.check_flight = !a.no_flight_check;
  extras.loop = a.loop;
  extras.resume = resume;
  // Ctrl-C ends the run as the sources' end would: held rows written, the score final.
  extras.stop = &CatchInterrupts();
  if (a.ui) {
    server::LiveOptions live;
    if (!a.layout.empty()) live.markers = ReadMarkerLayout(a.layout);
    hub = std::make_unique<server::LiveHub>(rig, game.players, live);
    web = std::make_unique<server::WebServer>(a.web.Options());
    web->ServeLive(hub.get());
    StartAndAnnounce(web.get(), a.web, "live view");
    extras.live = hub.get();
  }
  extras.on_gap = [](const std::string& source, const VideoGap& g) {
    const auto at = [](const std::optional<TimeNs>& t, const char* none) {
      return t ? fmt::format("{:.3f} s", ToSeconds(*t)) : std::string(none);
    };
    spdlog::warn("{}: damaged data skipped: {} frame(s) lost between {} and {} of the recording",
                 source, g.frames_lost, at(g.after, "its start"), at(g.before, "its end"));
  };
  extras.on_source = [](const std::string& source, const SourceEvent& e) {
    if (e.back) {
      spdlog::info("{}: back after {:.1f} s; tracked again", source, e.seconds_away);
    } else {
      spdlog::warn("{}: lost ({}); opening it again in the background, the other cameras go on",
                   source, e.reason);
    }
  };
  spdlog::info("tracking {} source(s) with {} ({} camera(s)) into {}", a.sources.size(), a.rig,
               rig.size(), a.out);
  const TrackRunSummary summary = RunTracking(
      rig, classes, a.sources, a.out, options, game,
      [](int64_t n) { spdlog::info("tracking: {} frame sets", n); }, extras);
  for (const auto& e : summary.sources_ended_with_error) spdlog::warn("source ended: {}", e);
  spdlog::info("{}", summary.Report());
  if (resume) {
    spdlog::info("resumed: {} rows and events were already in {} and are kept", summary.rows_found,
                 a.out);
  }
  if (summary.stopped) {
    spdlog::info("stopped by Ctrl-C; the run's files are complete{}",
                 WhyNotResumable(a).empty()
                     ? fmt::format(" (continue with: p4track track --resume {})", a.out)
                     : std::string());
  } else {
    WriteRunJson(a, true);
  }
  if (web && !summary.stopped) {
    spdlog::info(
        "the sources have ended; the live view stays at {} until Ctrl-C (replay the run "
        "with: p4track replay {})",
        web->Url(), a.out);
    WaitForInterrupt();
  }
  return 0;
}

}  // namespace

std::function<int()> AddTrackCommand(CLI::App& app) {
  auto args = std::make_shared<TrackArgs>();
  CLI::App* cmd =
      app.add_subcommand("track", "Track the ball in 3D from video files, cameras or streams");
  auto* rig = cmd->add_option("--rig", args->rig,
                              "Rig file (rig.yaml) of the cameras, in the sources' order")
                  ->check(CLI::ExistingFile);
  auto* out = cmd->add_option("--out", args->out,
                              "Output folder (trajectory.csv, detections.csv, events.jsonl, "
                              "score.json, run.json)");
  auto* sources = cmd->add_option("sources", args->sources,
                                  "One per camera: video file, /dev/videoN, rtsp://...");
  cmd->add_option("--resume", args->resume,
                  "Continue the run in this folder after a crash or kill, with its own options "
                  "(run.json): it is made again from its start, the rows its files hold are "
                  "checked and kept, the rest appended, the score carried on (files only)")
      ->check(CLI::ExistingDirectory)
      ->excludes(rig)
      ->excludes(out)
      ->excludes(sources);
  cmd->add_option("--classes", args->classes,
                  "Colour classes file (YAML; a run's ball_classes.yaml also gives the ball's lit "
                  "colour); default: --ball's")
      ->check(CLI::ExistingFile);
  cmd->add_option("--ball", args->ball,
                  "Ball colour when no --classes; auto: learnt from the recordings' first seconds "
                  "(saved as ball_classes.yaml in --out; an orange ball's colours for live "
                  "sources, one camera, or when the ball was not seen flying)")
      ->check(CLI::IsMember({"orange", "white", "yellow", "auto"}))
      ->capture_default_str();
  cmd->add_flag("--no-roi", args->no_roi, "Search the whole image every frame");
  cmd->add_flag("--no-confirm", args->no_confirm,
                "Start a track from any two measurements that agree (the paper's way) instead of "
                "waiting until the candidate has flown 10 cm in 4 frame sets");
  cmd->add_flag(
      "--no-flight-check", args->no_flight_check,
      "Write every measurement as measured, also one 6 cm or more off the ball's flight "
      "on both sides of it (2+ cameras; a wrong pair of views, an arm taken for the ball)");
  cmd->add_option("--detector", args->detector,
                  "colour: the colour tables (the paper's); masked: the tables where the picture "
                  "differs from a learnt background; coverage: the tables, each region measured "
                  "by coverage on the background; background: what differs from a "
                  "learnt background with the ball's colour mixed in, measured by coverage; auto: "
                  "background for a white ball, colour otherwise")
      ->check(CLI::IsMember({"auto", "colour", "masked", "coverage", "background"}))
      ->capture_default_str();
  cmd->add_option("--streaks", args->streaks,
                  "Look for the ball's faint blur streak along the path the filter predicts when "
                  "the window holds nothing of its size, and in the whole image with no track or "
                  "nothing where predicted (webcams' long exposures); auto: in cameras of 40 fps "
                  "or slower")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  cmd->add_option("--candidates", args->candidates,
                  "Candidate regions kept per camera and frame set (moving ones first)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--stride", args->stride, "Test every N-th pixel of a row")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  cmd->add_option("--filter", args->filter, "p4 (drag-aware) or paper (the paper's Q and R)")
      ->check(CLI::IsMember({"p4", "paper"}))
      ->capture_default_str();
  cmd->add_option("--threads", args->threads,
                  "Segment the cameras in parallel with this many threads (many or large cameras)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--no-single-camera", args->no_single_camera,
                "Never place the ball from one camera by its diameter");
  cmd->add_flag("--no-smoothing", args->no_smoothing,
                "One camera: write the filter's rows at once instead of refining each stroke "
                "(bearings, diameters, table contacts) about one stroke later");
  cmd->add_option("--epipolar-px", args->epipolar_px, "Epipolar distance bound, pixels")
      ->check(CLI::Range(0.5, 100.0))
      ->capture_default_str();
  cmd->add_option("--players", args->players, "Names of player A (x < 0) and B, e.g. Ana,Ben")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  cmd->add_option("--first-server", args->first_server, "Who serves first: A or B")
      ->check(CLI::IsMember({"A", "B"}))
      ->capture_default_str();
  cmd->add_option("--best-of", args->best_of, "Games in the match (odd)")
      ->check(CLI::IsMember({1, 3, 5, 7}))
      ->capture_default_str();
  cmd->add_flag("--no-sync", args->no_sync,
                "Take the cameras as in step when the rig gives no time offsets (default: found "
                "from the ball first, as `p4track sync` does)");
  cmd->add_flag("--rolling-shutter", args->rolling_shutter,
                "When syncing: the cameras read their rows out one after another (phones, most "
                "webcams); find each camera's line time from the ball too");
  cmd->add_option("--max-offset", args->max_offset,
                  "When syncing: search time offsets up to +- this many seconds")
      ->check(CLI::Range(0.05, 60.0))
      ->capture_default_str();
  cmd->add_flag("--no-referee", args->no_referee, "Track only: no events, no score");
  cmd->add_flag("--ui", args->ui,
                "Live view in the browser: every camera with its ROI, candidates and epipolar "
                "lines, the 3D table and ball, the score");
  cmd->add_option("--layout", args->layout,
                  "With --ui: show these calibration markers (markers.yaml) found in each "
                  "picture and where the rig projects them")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--realtime", args->realtime,
                "Pace video files at their own frame rate (a recording shown as live)");
  cmd->add_flag("--loop", args->loop,
                "Play the video files again and again (times continue) until Ctrl-C; with "
                "--realtime --ui, a recorded match shown for as long as anyone watches");
  args->web.Add(cmd);
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
