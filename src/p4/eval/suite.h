// The evaluation suite's scenes (`p4track eval-suite`): halls and cameras drawn from a seed within
// a family of rigs, so every accuracy figure is measured on many worlds, not on one look.
//
// Seeds are split once and for all: scene k (1-based) of the tuning set has seed k, of the
// checking set seed 1000 + k. Parameters may be chosen on the tuning set only; the checking set
// is measured and reported, never tuned on.
//
// Families (the targets of the README name them):
//   sports  2-3 cameras, 960x540 to 1920x1080, 60-240 fps, exposure 0.5-4 ms, orange or yellow
//           ball in a random hall;
//   webcam  2-3 webcams 640x480 at 25-30 fps, exposure 8 ms up to a whole frame, a cheap
//           encoder, lens distortion and vignetting, ball 3-6 px;
//   white   as sports with a white ball (a random hall, or the white and broadcast presets with
//           lamps, white lines, light walls and lettering);
//   mono    one camera, 1280x720 or 1920x1080 at 60-120 fps.
// Pure: no files, clocks or processes.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p4/geometry/rig.h"
#include "p4/io/run_files.h"

namespace p4 {

struct SuiteScene {
  std::string family;
  std::string set;  // "tuning" or "checking"
  uint64_t seed = 1;
  int cameras = 2;
  int width = 1280, height = 720;
  int fps = 120;
  double exposure_ms = 2.0;
  double fov_deg = 65.0;
  double noise = 2.0;
  int crf = 18;
  bool distortion = false;
  double vignetting = 0.0, defocus_px = 0.0, jitter_m = 0.3;
  std::string look = "random";
  std::string ball = "orange";  // orange, yellow or white
  double seconds = 6.0;         // of play
  int points = 2;

  // `p4track simulate` arguments for the scene (without the program and --out).
  std::vector<std::string> SimulateArgs() const;
  // The colour hint `p4track track --ball` takes for this scene's ball.
  std::string TrackBall() const { return ball; }
  nlohmann::ordered_json ToJson() const;
};

std::vector<std::string> SuiteFamilies();  // sports, webcam, white, mono

// Scene k (1-based) of a family and set. Throws p4::Error for an unknown family or set.
SuiteScene DrawSuiteScene(const std::string& family, const std::string& set, int k);

// Seed of scene k of a set (see above).
uint64_t SuiteSeed(const std::string& set, int k);

// The ball's diameter in pixels as a scene's cameras see it: per camera the median over the
// truth rows in play with the ball in the picture, then the smallest of the cameras (0 when no
// camera sees it).
double BallPixels(const Rig& rig, const std::vector<TruthRow>& truth);

}  // namespace p4
