#include "p4/eval/suite.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>

#include "p4/core/error.h"
#include "p4/core/robust.h"
#include "p4/core/table.h"

namespace p4 {
namespace {

struct Draw {
  std::mt19937_64 rng;
  double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  int I(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
  bool P(double p) { return U(0.0, 1.0) < p; }
};

double Round(double x, double step) { return std::round(x / step) * step; }

}  // namespace

std::vector<std::string> SuiteFamilies() {
  return {"sports", "webcam", "white", "mono", "unsync", "unsync-webcam", "phone"};
}

uint64_t SuiteSeed(const std::string& set, int k) {
  if (k < 1 || k > 999) throw Error(fmt::format("scene {}: must be in [1, 999]", k));
  if (set == "tuning") return static_cast<uint64_t>(k);
  if (set == "checking") return 1000 + static_cast<uint64_t>(k);
  throw Error("set '" + set + "': use tuning or checking");
}

SuiteScene DrawSuiteScene(const std::string& family, const std::string& set, int k) {
  SuiteScene s;
  s.family = family;
  s.set = set;
  s.seed = SuiteSeed(set, k);
  // One stream per family and seed: the families do not share draws.
  const std::vector<std::string> families = SuiteFamilies();
  const auto index = std::find(families.begin(), families.end(), family) - families.begin();
  const auto salt = static_cast<uint64_t>(index + 1) * 7919u;
  Draw d{std::mt19937_64(s.seed * 1000003ull + salt)};
  const auto sports_camera = [&]() {
    s.cameras = d.I(2, 3);
    const double size = d.U(0.0, 1.0);
    if (size < 0.3) {
      s.width = 960, s.height = 540;
    } else if (size < 0.8) {
      s.width = 1280, s.height = 720;
    } else {
      s.width = 1920, s.height = 1080;
    }
    const int rates[] = {60, 90, 120, 120, 240};
    s.fps = rates[d.I(0, 4)];
    s.exposure_ms = Round(d.U(0.5, std::min(4.0, 1000.0 / s.fps)), 0.1);
    // The ball stays >= 5 px across at the far end: narrower views on smaller pictures.
    s.fov_deg = Round(d.U(45.0, s.width >= 1280 ? 80.0 : 60.0), 1.0);
    s.noise = Round(d.U(1.0, 3.5), 0.1);
    s.crf = d.I(18, 26);
    s.distortion = d.P(0.4);
    s.vignetting = Round(d.U(0.0, 0.35), 0.01);
    s.defocus_px = d.P(0.3) ? Round(d.U(0.3, 1.0), 0.1) : 0.0;
    // At most ~900 frames a camera: the suite's time goes where the variety is.
    s.seconds = Round(std::min(6.0, 900.0 / s.fps), 0.1);
  };
  // Free-running cameras: camera 1 started up to 5 s before camera 0 (both record all the
  // play) at a random phase, drifting, its stamps jittered by up to `jitter_ms`, a few frames
  // lost; the twin is the same play by cameras triggered in step. 10 s of play.
  const auto out_of_step = [&](double jitter_ms) {
    s.start_offsets_s.assign(static_cast<std::size_t>(s.cameras), 0.0);
    s.drift_ppm.assign(static_cast<std::size_t>(s.cameras), 0.0);
    for (int c = 1; c < s.cameras; ++c) {
      s.start_offsets_s[c] = Round(-d.U(0.05, 4.9), 1e-5);
      s.drift_ppm[c] = Round(d.U(-50.0, 50.0), 0.1);
    }
    s.stamp_jitter_ms = Round(d.U(0.0, jitter_ms), 0.01);
    s.drop_rate = Round(d.U(0.0, 0.02), 0.001);
    s.seconds = 10.0;
    s.twin = "in-step";
  };
  if (family == "sports") {
    sports_camera();
    s.ball = d.P(0.75) ? "orange" : "yellow";
  } else if (family == "webcam" || family == "unsync-webcam") {
    s.cameras = d.I(2, 3);
    s.width = 640, s.height = 480;
    s.fps = d.P(0.5) ? 25 : 30;
    s.exposure_ms = Round(d.U(8.0, 1000.0 / s.fps), 0.1);
    s.fov_deg = Round(d.U(55.0, 75.0), 1.0);
    s.noise = Round(d.U(2.5, 5.0), 0.1);
    s.crf = d.I(23, 32);
    s.distortion = d.P(0.7);
    s.vignetting = Round(d.U(0.1, 0.4), 0.01);
    s.defocus_px = Round(d.U(0.3, 1.0), 0.1);
    s.seconds = 8.0;
    s.ball = "orange";
    if (family == "unsync-webcam") out_of_step(1.0);
  } else if (family == "white") {
    sports_camera();
    s.ball = "white";
    const double look = d.U(0.0, 1.0);
    s.look = look < 0.5 ? "random" : (look < 0.8 ? "white" : "broadcast");
  } else if (family == "mono") {
    sports_camera();
    s.cameras = 1;
    s.ball = d.P(0.75) ? "orange" : "yellow";
  } else if (family == "unsync") {
    sports_camera();
    s.cameras = 2;
    if (s.width > 1280) s.width = 1280, s.height = 720;
    s.fps = 60;
    s.camera_fps = {60, d.P(1.0 / 3.0) ? 120 : 60};
    s.exposure_ms = Round(d.U(0.5, 4.0), 0.1);
    s.ball = d.P(0.75) ? "orange" : "yellow";
    out_of_step(0.5);
  } else if (family == "phone") {
    sports_camera();
    s.cameras = 2;
    s.width = 1920, s.height = 1080;
    s.fps = d.P(0.5) ? 30 : 60;
    s.exposure_ms = Round(d.U(1.0, 4.0), 0.1);
    s.fov_deg = Round(d.U(60.0, 75.0), 1.0);
    s.distortion = true;
    s.ball = d.P(0.75) ? "orange" : "yellow";
    out_of_step(1.0);
    // Each sensor is read out within the frame: 15-25 ms at 30 fps, 10-16 ms at 60 fps (two
    // phone models: two readouts).
    for (int c = 0; c < s.cameras; ++c) {
      s.rolling_shutter_ms.push_back(Round(s.fps == 30 ? d.U(15.0, 25.0) : d.U(10.0, 16.0), 0.1));
    }
    s.twin = "global-shutter";
  } else {
    throw Error("family '" + family + "': use one of " +
                fmt::format("{}", fmt::join(families, ", ")));
  }
  return s;
}

std::vector<std::string> SuiteScene::SimulateArgs() const {
  const std::pair<const char*, std::string> options[] = {
      {"--cameras", std::to_string(cameras)},
      {"--size", fmt::format("{}x{}", width, height)},
      {"--fps", std::to_string(fps)},
      {"--exposure-ms", fmt::format("{:.2f}", exposure_ms)},
      {"--fov", fmt::format("{:.1f}", fov_deg)},
      {"--noise", fmt::format("{:.2f}", noise)},
      {"--crf", std::to_string(crf)},
      {"--vignetting", fmt::format("{:.2f}", vignetting)},
      {"--defocus", fmt::format("{:.2f}", defocus_px)},
      {"--jitter", fmt::format("{:.2f}", jitter_m)},
      {"--look", look},
      {"--ball", ball},
      {"--seed", std::to_string(seed)},
      {"--points", std::to_string(points)},
      {"--max-duration", fmt::format("{:.2f}", seconds)},
  };
  std::vector<std::string> a = {"simulate"};
  for (const auto& [flag, value] : options) a.insert(a.end(), {flag, value});
  if (distortion) a.push_back("--distortion");
  const auto list = [&](const char* flag, const auto& values, const char* format) {
    if (values.empty()) return;
    std::string joined;
    for (const auto& v : values) {
      if (!joined.empty()) joined += ',';
      joined += fmt::format(fmt::runtime(format), v);
    }
    a.insert(a.end(), {flag, joined});
  };
  list("--start-offsets", start_offsets_s, "{:.5f}");
  list("--camera-fps", camera_fps, "{}");
  list("--drift-ppm", drift_ppm, "{:.1f}");
  list("--rolling-shutter-ms", rolling_shutter_ms, "{:.3f}");
  const std::pair<const char*, double> timing[] = {{"--drop-rate", drop_rate},
                                                   {"--stamp-jitter-ms", stamp_jitter_ms}};
  for (const auto& [flag, value] : timing) {
    if (value > 0.0) a.insert(a.end(), {flag, fmt::format("{:.3f}", value)});
  }
  return a;
}

SuiteScene SuiteScene::Twin() const {
  if (twin != "in-step" && twin != "global-shutter") {
    throw Error("scene " + family + "-" + std::to_string(seed) + ": no twin");
  }
  SuiteScene t = *this;
  t.twin.clear();
  t.rolling_shutter_ms.clear();
  if (twin == "in-step") {
    t.start_offsets_s.clear();
    t.drift_ppm.clear();
    t.drop_rate = 0.0;
    t.stamp_jitter_ms = 0.0;
  }
  return t;
}

nlohmann::ordered_json SuiteScene::ToJson() const {
  return {{"family", family},
          {"set", set},
          {"seed", seed},
          {"cameras", cameras},
          {"size", fmt::format("{}x{}", width, height)},
          {"fps", fps},
          {"exposure_ms", exposure_ms},
          {"fov_deg", fov_deg},
          {"noise", noise},
          {"crf", crf},
          {"distortion", distortion},
          {"vignetting", vignetting},
          {"defocus_px", defocus_px},
          {"look", look},
          {"ball", ball},
          {"seconds", seconds},
          {"start_offsets_s", start_offsets_s},
          {"camera_fps", camera_fps},
          {"drift_ppm", drift_ppm},
          {"rolling_shutter_ms", rolling_shutter_ms},
          {"drop_rate", drop_rate},
          {"stamp_jitter_ms", stamp_jitter_ms},
          {"twin", twin}};
}

double BallPixels(const Rig& rig, const std::vector<TruthRow>& truth) {
  double smallest = 0.0;
  for (const Camera& camera : rig.cameras) {
    std::vector<double> sizes;
    for (const TruthRow& row : truth) {
      if (!row.in_play) continue;
      const Eigen::Vector3d c = camera.cam_from_world * row.position;
      const auto px = camera.Project(row.position);
      if (c.z() <= 0.1 || !px || !camera.InImage(*px)) continue;
      sizes.push_back(camera.fx * table::kBallDiameter / c.z());
    }
    if (sizes.empty()) continue;
    const double median = MedianInPlace(sizes);
    smallest = smallest == 0.0 ? median : std::min(smallest, median);
  }
  return smallest;
}

SuiteTarget TargetOf(const std::string& family) {
  if (family == "sports") return {0.99, 0.005, 5.0, 3.0};
  if (family == "webcam") return {0.95, 1.0, 15.0, 1e9};
  if (family == "white") return {0.98, 0.01, 1e9, 1e9};
  if (family == "mono") return {0.0, 1.0, 50.0, 1e9};
  if (family == "unsync") return {0.99, 1.0, 5.0, 1e9, 0.5, 1.1};
  if (family == "unsync-webcam") return {0.0, 1.0, 15.0, 1e9, 0.5};
  if (family == "phone") return {0.0, 1.0, 1e9, 1e9, 0.5, 1.5};
  throw Error(fmt::format("no targets for family '{}' (families: {})", family,
                          fmt::join(SuiteFamilies(), ", ")));
}

namespace {

// Which per-scene bounds of a target apply: recall, false rows, RMSE, sync, twin.
std::array<bool, 5> Applies(const SuiteTarget& t) {
  return {t.min_recall > 0.0, t.max_fp < 1.0, t.max_rmse_mm < 1e9, t.max_sync_ms < 1e9,
          t.max_twin_ratio < 1e9};
}

// The counts in that order.
std::array<int, 5> Met(const TargetCounts& c) { return {c.recall, c.fp, c.rmse, c.sync, c.twin}; }

}  // namespace

void CountTargetsMet(const SuiteTarget& target, const SceneFigures& scene, TargetCounts* counts) {
  ++counts->scenes;
  if (!scene.evaluated) return;
  const auto at_most = [](const std::optional<double>& v, double bound) {
    return v && *v <= bound;
  };
  const std::array<bool, 5> met = {
      scene.recall && *scene.recall >= target.min_recall,
      at_most(scene.false_positive_rate, target.max_fp), at_most(scene.rmse_mm, target.max_rmse_mm),
      at_most(scene.sync_ms, target.max_sync_ms), at_most(scene.twin_ratio, target.max_twin_ratio)};
  const std::array<int*, 5> count = {&counts->recall, &counts->fp, &counts->rmse, &counts->sync,
                                     &counts->twin};
  const std::array<bool, 5> applies = Applies(target);
  bool all = true;
  for (std::size_t i = 0; i < met.size(); ++i) {
    if (!applies[i]) continue;
    if (met[i]) ++*count[i];
    all = all && met[i];
  }
  if (all) ++counts->all;
}

std::string TargetCounts::Describe(const SuiteTarget& target) const {
  const std::array<bool, 5> applies = Applies(target);
  const std::array<const char*, 5> names = {"recall", "FP", "RMSE", "sync", "twin"};
  const std::array<int, 5> values = Met(*this);
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (applies[i]) parts.push_back(fmt::format("{} {}", names[i], values[i]));
  }
  if (parts.size() > 1) parts.push_back(fmt::format("all {}", all));
  return fmt::format("{} of {}", fmt::join(parts, ", "), scenes);
}

nlohmann::ordered_json TargetCounts::ToJson(const SuiteTarget& target) const {
  const std::array<bool, 5> applies = Applies(target);
  const std::array<const char*, 5> names = {"recall", "false_positive_rate", "rmse", "sync",
                                            "twin_ratio"};
  const std::array<int, 5> values = Met(*this);
  nlohmann::ordered_json out = {{"scenes", scenes}};
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (applies[i]) out[names[i]] = values[i];
  }
  out["all"] = all;
  return out;
}

bool FloorHasBallsHue(const Eigen::Vector3d& floor, const Eigen::Vector3d& ball) {
  // Hue in degrees and saturation of an RGB colour (HSV).
  const auto hue_saturation = [](const Eigen::Vector3d& c) {
    const double hi = c.maxCoeff(), lo = c.minCoeff(), d = hi - lo;
    double hue = 0.0;
    if (d > 0.0) {
      if (hi == c.x()) {
        hue = std::fmod((c.y() - c.z()) / d + 6.0, 6.0);
      } else if (hi == c.y()) {
        hue = (c.z() - c.x()) / d + 2.0;
      } else {
        hue = (c.x() - c.y()) / d + 4.0;
      }
    }
    return std::pair{60.0 * hue, hi > 0.0 ? d / hi : 0.0};
  };
  const auto [floor_hue, floor_saturation] = hue_saturation(floor);
  const auto [ball_hue, ball_saturation] = hue_saturation(ball);
  const double apart = std::abs(floor_hue - ball_hue);
  return ball_saturation > 0.0 && floor_saturation > 0.4 && std::min(apart, 360.0 - apart) < 25.0;
}

std::vector<std::string> SceneGroups(const SuiteScene& scene, double ball_px,
                                     std::optional<bool> floor_has_balls_hue) {
  const auto band = [](double v, std::initializer_list<double> edges, const char* unit) {
    double below = 0.0;
    for (const double edge : edges) {
      if (v < edge) {
        return below == 0.0 ? fmt::format("under {:g} {}", edge, unit)
                            : fmt::format("{:g}-{:g} {}", below, edge, unit);
      }
      below = edge;
    }
    return fmt::format("{:g} {} and over", below, unit);
  };
  std::vector<std::string> groups = {
      fmt::format("{} camera{}", scene.cameras, scene.cameras == 1 ? "" : "s"),
      fmt::format("{} fps", scene.fps), "exposure " + band(scene.exposure_ms, {1, 2, 4, 10}, "ms"),
      "ball " + band(ball_px, {6, 10, 15}, "px"), scene.ball + " ball"};
  if (floor_has_balls_hue) {
    groups.push_back(*floor_has_balls_hue ? "floor of the ball's hue" : "floor of another hue");
  }
  return groups;
}

}  // namespace p4
