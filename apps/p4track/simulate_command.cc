// p4track simulate: renders simulated (or real, --trajectory) table-tennis play from N cameras,
// with exact ground truth (DESIGN.md "Files").
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>

#include "commands.h"
#include "p4/calib/aruco_markers.h"
#include "p4/core/error.h"
#include "p4/io/flight_file.h"
#include "p4/io/rig_file.h"
#include "p4/io/truth_files.h"
#include "p4/io/video_writer.h"
#include "p4/sim/camera_layout.h"
#include "p4/sim/look.h"
#include "p4/sim/match.h"
#include "p4/sim/renderer.h"

namespace p4::app {
namespace {

struct SimulateArgs {
  std::string out;
  int cameras = 2;
  std::string size = "1280x720";
  int fps = 120;
  int points = 4;
  uint64_t seed = 1;
  std::string codec = "h264";
  std::string ball;  // the look's own unless given
  std::string look = "club";
  double vignetting = 0.0, defocus = 0.0, fov = 0.0, jitter = 0.0;
  int crf = 18;
  bool markers = false;
  double marker_size = 0.12;
  std::string dictionary = "DICT_4X4_50";
  bool orange_shirt = false;
  bool no_players = false;
  bool distortion = false;
  double noise = 2.0;
  double exposure_ms = 2.0;
  int best_of = 5;
  std::string first_server = "A";
  double gap = 1.0;
  double max_duration = 0.0;
  std::string trajectory;
  int threads = 0;
};

int Run(const SimulateArgs& a) {
  const auto started = std::chrono::steady_clock::now();
  int width = 0, height = 0;
  ParseSize(a.size, "--size", &width, &height);
  if (a.fps < 1 || a.fps > 1000) throw Error("--fps: must be in [1, 1000]");
  const double exposure = a.exposure_ms / 1000.0;
  if (!(exposure >= 0.0) || exposure > 1.0 / a.fps) {
    throw Error(fmt::format("--exposure-ms: must be between 0 and a frame ({:.2f} ms), got {}",
                            1000.0 / a.fps, a.exposure_ms));
  }
  const VideoCodec codec = a.codec == "ffv1" ? VideoCodec::kFFV1 : VideoCodec::kH264;

  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec) throw Error(a.out + ": cannot create the folder (" + ec.message() + ")");
  const auto file = [&](const std::string& name) { return (fs::path(a.out) / name).string(); };

  // The true world: simulated play, or a real flight.
  sim::Trajectory trajectory;
  std::vector<sim::TruthEvent> events;
  nlohmann::json score_json;
  double duration = 0.0;
  if (!a.trajectory.empty()) {
    RealFlight flight = ReadTt3dFlight(a.trajectory, 0.2);
    trajectory = std::move(flight.trajectory);
    events = std::move(flight.bounces);
    duration = flight.end_s + 0.2;
    score_json = {{"source", a.trajectory}, {"note", "a real flight: no match is played"}};
    spdlog::info("real flight {}: {:.2f} s, {} bounce(s)", a.trajectory, flight.end_s - 0.2,
                 events.size());
  } else {
    sim::MatchOptions options;
    options.points = a.points;
    options.seed = a.seed;
    options.best_of = a.best_of;
    options.first_server = a.first_server.empty() ? '?' : a.first_server[0];
    options.gap_s = a.gap;
    std::string why;
    if (!options.IsValid(&why)) throw Error("simulate: " + why);
    spdlog::info("simulating {} point(s), seed {}", a.points, a.seed);
    sim::MatchResult match = sim::SimulateMatch(options);
    trajectory = std::move(match.trajectory);
    events = std::move(match.events);
    duration = match.duration;
    score_json = ScoreToJson(match.score, match.points_played);
  }
  if (a.max_duration > 0.0 && a.max_duration < duration) {
    duration = a.max_duration;
    std::erase_if(events, [&](const sim::TruthEvent& e) { return e.t >= duration; });
    score_json["truncated_at_s"] = duration;
  }
  const int64_t frames = static_cast<int64_t>(std::floor(duration * a.fps));

  sim::ClubRigOptions placing;
  placing.hfov_deg = a.fov;
  placing.jitter_m = a.jitter;
  placing.seed = a.seed;
  const Rig rig = sim::ClubRig(a.cameras, width, height, a.distortion, placing);
  WriteRig(rig, file("rig.yaml"));
  WriteTruthCsv(file("truth.csv"), trajectory, a.fps, frames);
  WriteEventsJsonl(file("truth_events.jsonl"), events);
  WriteJson(file("truth_score.json"), score_json);

  sim::SceneOptions scene;
  scene.look = a.look == "random" ? sim::RandomLook(a.seed, a.ball.empty() ? "any" : a.ball)
                                  : sim::PresetLook(a.look);
  if (a.look != "random" && a.ball == "any") {
    throw Error("--ball any: the colour is drawn with --look random only; with --look " + a.look +
                " use orange, white or yellow");
  }
  if (a.look != "random" && !a.ball.empty()) scene.look.ball = sim::BallColour(a.ball);
  if (a.orange_shirt) scene.look.shirt_b = sim::BallColour("orange");
  scene.players = !a.no_players;
  WriteJson(file("look.json"), LookToJson(scene.look));
  if (a.markers) {
    scene.markers = sim::TableCornerMarkers(a.marker_size);
    for (auto& m : scene.markers) m.black = ArucoModules(a.dictionary, m.id, &m.cells);
    WriteMarkerLayout(file("markers.yaml"), scene.markers, a.dictionary);
  }
  sim::RenderOptions render;
  render.noise_sigma_luma = a.noise;
  render.noise_sigma_chroma = 0.75 * a.noise;
  render.static_supersampling = a.markers ? 4 : 3;
  render.seed = a.seed;
  render.vignetting = a.vignetting;
  render.defocus_px = a.defocus;
  std::string why;
  if (!render.IsValid(&why)) throw Error("simulate: " + why);

  // One thread per camera (up to the core count); each renders and encodes its own video.
  const int cores = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  const int workers = std::min(cores, rig.size());
  std::atomic<int64_t> done{0};
  std::atomic<int> next_camera{0};
  std::vector<std::string> errors(rig.size());
  std::vector<std::vector<float>> visibility(rig.size(), std::vector<float>(frames, 0.0f));
  const auto work = [&]() {
    for (int c = next_camera++; c < rig.size(); c = next_camera++) {
      try {
        sim::CameraRenderer renderer(rig.cameras[c], scene, render);
        VideoWriterOptions vo;
        vo.width = width;
        vo.height = height;
        vo.fps = a.fps;
        vo.codec = codec;
        vo.crf = a.crf;
        vo.threads = std::max(1, cores / rig.size());
        VideoWriter writer(file(rig.cameras[c].name + VideoExtension(codec)), vo);
        I420Image image(width, height);
        for (int64_t k = 0; k < frames; ++k) {
          const double t = static_cast<double>(k) / a.fps;
          visibility[c][k] = static_cast<float>(
              renderer.Render(sim::ContentAt(trajectory, t, exposure), k, &image));
          writer.Write(image);
          ++done;
        }
        writer.Close();
      } catch (const std::exception& e) {
        errors[c] = e.what();
        done += frames;
      }
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(workers);
  for (int i = 0; i < workers; ++i) threads.emplace_back(work);
  const int64_t total = frames * rig.size();
  auto last = std::chrono::steady_clock::now();
  while (done < total) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (std::chrono::steady_clock::now() - last > std::chrono::seconds(2)) {
      last = std::chrono::steady_clock::now();
      spdlog::info("rendering: {}/{} frames ({:.0f}%)", done.load(), total, 100.0 * done / total);
    }
  }
  for (auto& t : threads) t.join();
  for (const auto& e : errors) {
    if (!e.empty()) throw Error(e);
  }
  WriteVisibilityCsv(file("truth_visibility.csv"), rig, visibility, a.fps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  spdlog::info(
      "wrote {}: {} camera(s) x {} frames ({}x{} at {} fps, {:.2f} s of play), {} events "
      "in {:.1f} s",
      a.out, rig.size(), frames, width, height, a.fps, duration, events.size(), seconds);
  return 0;
}

}  // namespace

std::function<int()> AddSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Render simulated table-tennis play from N cameras with exact ground truth");
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->add_option("--cameras", args->cameras, "Number of cameras (club positions)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--fps", args->fps, "Frames per second")->capture_default_str();
  cmd->add_option("--points", args->points, "Points to play")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (same seed, same truth)")
      ->capture_default_str();
  cmd->add_option("--codec", args->codec, "h264 (.mp4) or ffv1 (lossless .mkv)")
      ->check(CLI::IsMember({"h264", "ffv1"}))
      ->capture_default_str();
  cmd->add_option("--ball", args->ball, "Ball colour (default: the look's; random: any)")
      ->check(CLI::IsMember({"orange", "white", "yellow", "any"}));
  cmd->add_option("--look", args->look,
                  "The hall's look: club, overhead, banner, white, broadcast, dim, or random "
                  "(drawn from --seed: light, colours, banners, lamps, shirts, a spare ball)")
      ->check(CLI::IsMember({"club", "overhead", "banner", "white", "broadcast", "dim", "random"}))
      ->capture_default_str();
  cmd->add_option("--fov", args->fov, "Field of view across the picture, degrees (0: about 65)")
      ->check(CLI::Range(0.0, 120.0))
      ->capture_default_str();
  cmd->add_option("--jitter", args->jitter,
                  "Move each camera by up to this many metres (by --seed)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--vignetting", args->vignetting, "Brightness lost at the picture's corners")
      ->check(CLI::Range(0.0, 0.9))
      ->capture_default_str();
  cmd->add_option("--defocus", args->defocus, "Lens blur, Gaussian sigma in pixels")
      ->check(CLI::Range(0.0, 5.0))
      ->capture_default_str();
  cmd->add_option("--crf", args->crf, "H.264 quality (18 good, 32 a cheap webcam's stream)")
      ->check(CLI::Range(0, 51))
      ->capture_default_str();
  cmd->add_flag("--markers", args->markers,
                "Lay ArUco markers on the table corners (markers.yaml)");
  cmd->add_option("--marker-size", args->marker_size, "Marker side, metres")
      ->check(CLI::Range(0.03, 0.3))
      ->capture_default_str();
  cmd->add_option("--dictionary", args->dictionary, "ArUco dictionary")->capture_default_str();
  cmd->add_flag("--orange-shirt", args->orange_shirt, "Player B wears an orange-ish shirt");
  cmd->add_flag("--no-players", args->no_players, "Leave the players out");
  cmd->add_flag("--distortion", args->distortion, "Give the cameras webcam-like lens distortion");
  cmd->add_option("--noise", args->noise, "Sensor noise, 8-bit levels (sigma)")
      ->check(CLI::Range(0.0, 20.0))
      ->capture_default_str();
  cmd->add_option("--exposure-ms", args->exposure_ms,
                  "Exposure time (a sports setting; webcams on auto may use 8 ms or more)")
      ->capture_default_str();
  cmd->add_option("--best-of", args->best_of, "Games in the match (odd)")->capture_default_str();
  cmd->add_option("--first-server", args->first_server, "A or B")
      ->check(CLI::IsMember({"A", "B"}))
      ->capture_default_str();
  cmd->add_option("--gap", args->gap, "Seconds without a ball between points")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--max-duration", args->max_duration, "Stop the scene after this many seconds");
  cmd->add_option("--trajectory", args->trajectory,
                  "Replay a real flight (tt3d CSV) instead of play")
      ->check(CLI::ExistingFile);
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
