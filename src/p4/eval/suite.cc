#include "p4/eval/suite.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "p4/core/error.h"
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

std::vector<std::string> SuiteFamilies() { return {"sports", "webcam", "white", "mono"}; }

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
  if (family == "sports") {
    sports_camera();
    s.ball = d.P(0.75) ? "orange" : "yellow";
  } else if (family == "webcam") {
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
  } else if (family == "white") {
    sports_camera();
    s.ball = "white";
    const double look = d.U(0.0, 1.0);
    s.look = look < 0.5 ? "random" : (look < 0.8 ? "white" : "broadcast");
  } else if (family == "mono") {
    sports_camera();
    s.cameras = 1;
    s.ball = d.P(0.75) ? "orange" : "yellow";
  } else {
    throw Error("family '" + family + "': use sports, webcam, white or mono");
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
  return a;
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
          {"seconds", seconds}};
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
    std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2),
                     sizes.end());
    const double median = sizes[sizes.size() / 2];
    smallest = smallest == 0.0 ? median : std::min(smallest, median);
  }
  return smallest;
}

}  // namespace p4
