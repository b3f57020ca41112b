// p4track simulate: renders simulated (or real, --trajectory) table-tennis play from N cameras,
// with exact ground truth (DESIGN.md "Files").
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <numeric>
#include <random>
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
  // Cameras out of step (beyond the paper): each camera's start, rate and clock drift; camera 0
  // is the rig's clock.
  std::string start_offsets, camera_fps, drift_ppm, rolling_shutter_ms;
  double drop_rate = 0.0, stamp_jitter_ms = 0.0;
};

// One number per camera from "a,b,c" (empty: `fallback` for all).
std::vector<double> PerCamera(const std::string& text, int cameras, double fallback,
                              const std::string& flag) {
  if (text.empty()) return std::vector<double>(cameras, fallback);
  std::vector<double> values;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    try {
      std::size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw Error(fmt::format("{}: '{}' is not a number", flag, item));
    }
    begin = end + 1;
  }
  if (static_cast<int>(values.size()) != cameras) {
    throw Error(fmt::format("{}: {} value(s) for {} camera(s)", flag, values.size(), cameras));
  }
  return values;
}

// When each camera's frames were exposed, in world (truth) time.
struct CameraTiming {
  double start_s = 0.0;  // world time of its first frame (stamp 0)
  int fps = 0;
  double rate = 1.0;  // world seconds per second of its clock
  double line_time_s = 0.0;

  double TopRow(int64_t k) const { return start_s + rate * static_cast<double>(k) / fps; }
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
  // Per camera timing; camera 0 is the rig's clock (truth rows at its frames).
  const std::vector<double> starts = PerCamera(a.start_offsets, a.cameras, 0.0, "--start-offsets");
  const std::vector<double> rates = PerCamera(a.camera_fps, a.cameras, a.fps, "--camera-fps");
  const std::vector<double> drifts = PerCamera(a.drift_ppm, a.cameras, 0.0, "--drift-ppm");
  if (starts[0] != 0.0 || drifts[0] != 0.0) {
    throw Error("--start-offsets, --drift-ppm: camera 0 is the rig's clock (0 for it)");
  }
  std::vector<CameraTiming> timing(a.cameras);
  // One readout for every camera, or one each (phones of two models).
  const bool one_readout = a.rolling_shutter_ms.find(',') == std::string::npos;
  const std::vector<double> readouts =
      PerCamera(a.rolling_shutter_ms, one_readout ? 1 : a.cameras, 0.0, "--rolling-shutter-ms");
  const auto readout_ms = [&](int c) { return readouts.size() == 1 ? readouts[0] : readouts[c]; };
  bool in_step = a.drop_rate == 0.0 && a.stamp_jitter_ms == 0.0;
  for (int c = 0; c < a.cameras; ++c) {
    if (std::abs(starts[c]) > 60.0) throw Error("--start-offsets: within +-60 s");
    if (rates[c] < 1 || rates[c] > 1000 || rates[c] != std::floor(rates[c])) {
      throw Error(
          fmt::format("--camera-fps: whole frames a second in [1, 1000], got {}", rates[c]));
    }
    if (std::abs(drifts[c]) > 1000.0) throw Error("--drift-ppm: within +-1000 ppm");
    if (readout_ms(c) < 0.0 || readout_ms(c) > 100.0) {
      throw Error(fmt::format("--rolling-shutter-ms: within [0, 100] ms, got {}", readout_ms(c)));
    }
    timing[c] = {starts[c], static_cast<int>(rates[c]), 1.0 + 1e-6 * drifts[c],
                 readout_ms(c) / 1000.0 / height};
    in_step = in_step && readout_ms(c) == 0.0;
    if (readout_ms(c) > 1000.0 / timing[c].fps) {
      throw Error(fmt::format(
          "--rolling-shutter-ms: camera {}'s readout ({} ms) is longer than its frame ({:.2f} "
          "ms); a sensor reads a frame out within its period",
          c, readout_ms(c), 1000.0 / timing[c].fps));
    }
    if (exposure > 1.0 / timing[c].fps) {
      throw Error(fmt::format("--exposure-ms: longer than camera {}'s frame ({:.2f} ms)", c,
                              1000.0 / timing[c].fps));
    }
    in_step = in_step && starts[c] == 0.0 && timing[c].fps == timing[0].fps && drifts[c] == 0.0;
  }
  if (a.stamp_jitter_ms > 0.25 * 1000.0 / *std::max_element(rates.begin(), rates.end())) {
    throw Error("--stamp-jitter-ms: at most a quarter of the fastest camera's frame");
  }
  const int truth_fps = timing[0].fps;
  const int64_t frames = static_cast<int64_t>(std::floor(duration * truth_fps));

  sim::ClubRigOptions placing;
  placing.hfov_deg = a.fov;
  placing.jitter_m = a.jitter;
  placing.seed = a.seed;
  const Rig rig = sim::ClubRig(a.cameras, width, height, a.distortion, placing);
  WriteRig(rig, file("rig.yaml"));
  if (!in_step) {
    // What a user's rig would say once synchronised: the true clocks (rig.yaml has none).
    Rig synced = rig;
    for (int c = 0; c < rig.size(); ++c) {
      CameraClock& clock = synced.cameras[c].clock;
      clock.time_offset_s = timing[c].start_s;
      clock.has_offset = true;
      clock.clock_rate = timing[c].rate;
      clock.line_time_s = timing[c].line_time_s;
    }
    WriteRig(synced, file("rig_synced.yaml"));
  }
  WriteTruthCsv(file("truth.csv"), trajectory, truth_fps, frames);
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
  // Each camera's frames over the scene's world time [0, duration).
  std::vector<int64_t> camera_frames(rig.size());
  for (int c = 0; c < rig.size(); ++c) {
    const CameraTiming& w = timing[c];
    camera_frames[c] = std::max<int64_t>(
        0, static_cast<int64_t>(std::ceil((duration - w.start_s) / w.rate * w.fps)));
  }
  const int64_t total = std::accumulate(camera_frames.begin(), camera_frames.end(), int64_t{0});
  const auto work = [&]() {
    for (int c = next_camera++; c < rig.size(); c = next_camera++) {
      const CameraTiming& w = timing[c];
      try {
        sim::CameraRenderer renderer(rig.cameras[c], scene, render);
        VideoWriterOptions vo;
        vo.width = width;
        vo.height = height;
        vo.fps = w.fps;
        vo.codec = codec;
        vo.crf = a.crf;
        vo.threads = std::max(1, cores / rig.size());
        if (a.stamp_jitter_ms > 0.0) vo.time_base_hz = 90000;
        VideoWriter writer(file(rig.cameras[c].name + VideoExtension(codec)), vo);
        I420Image image(width, height);
        std::mt19937_64 rng(a.seed * 7919u + static_cast<uint64_t>(c));
        std::normal_distribution<double> jitter(0.0, a.stamp_jitter_ms / 1000.0);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        const Camera& camera = rig.cameras[c];
        for (int64_t k = 0; k < camera_frames[c]; ++k, ++done) {
          if (k > 0 && uniform(rng) < a.drop_rate) continue;  // lost: no frame, no stamp
          // Rolling shutter: the ball is drawn at the time its own row was exposed.
          double t = w.TopRow(k);
          if (w.line_time_s > 0.0) {
            double row = 0.5 * height;
            for (int i = 0; i < 3; ++i) {
              const auto at = trajectory.At(w.TopRow(k) + w.line_time_s * row);
              const auto px = at ? camera.Project(at->position) : std::nullopt;
              if (px) row = std::clamp(px->y(), 0.0, height - 1.0);
            }
            t = w.TopRow(k) + w.line_time_s * row;
          }
          const double seen = renderer.Render(sim::ContentAt(trajectory, t, exposure), k, &image);
          // The truth row nearest this frame, within half of its period, takes its visibility.
          const auto row = std::llround(w.TopRow(k) * truth_fps);
          if (row >= 0 && row < frames &&
              std::abs(static_cast<double>(row) / truth_fps - w.TopRow(k)) <= 0.5 / w.fps) {
            visibility[c][row] = static_cast<float>(seen);
          }
          // The first frame's stamp is the clock's zero (a reader counts from it): unjittered.
          const double stamp = static_cast<double>(k) / w.fps + (k > 0 ? jitter(rng) : 0.0);
          writer.Write(image, FromSeconds(stamp));
        }
        writer.Close();
      } catch (const std::exception& e) {
        errors[c] = e.what();
        done += camera_frames[c];
      }
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(workers);
  for (int i = 0; i < workers; ++i) threads.emplace_back(work);
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
  WriteVisibilityCsv(file("truth_visibility.csv"), rig, visibility, truth_fps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  spdlog::info(
      "wrote {}: {} camera(s) x {} frames ({}x{} at {} fps, {:.2f} s of play), {} events "
      "in {:.1f} s",
      a.out, rig.size(), frames, width, height, truth_fps, duration, events.size(), seconds);
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
  cmd->add_option("--start-offsets", args->start_offsets,
                  "Cameras out of step: when each camera's recording started, seconds after "
                  "camera 0's, one per camera (e.g. 0,0.1234); rig.yaml then has no clocks and "
                  "rig_synced.yaml the true ones");
  cmd->add_option("--camera-fps", args->camera_fps,
                  "Frames per second of each camera (e.g. 60,120; default --fps for all)");
  cmd->add_option("--drift-ppm", args->drift_ppm,
                  "Each camera's clock drift against camera 0's, parts per million (e.g. 0,40)");
  cmd->add_option("--rolling-shutter-ms", args->rolling_shutter_ms,
                  "Rolling shutter: time to read a whole frame out, top row to bottom (phones: "
                  "15-30 ms); one for all cameras or one each (e.g. 12,18)");
  cmd->add_option("--drop-rate", args->drop_rate, "Share of frames each camera loses")
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--stamp-jitter-ms", args->stamp_jitter_ms,
                  "Noise of the timestamps written (sigma, ms); the exposures stay regular and the "
                  "first frame's stamp is exact")
      ->check(CLI::Range(0.0, 10.0));
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
