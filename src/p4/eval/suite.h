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
// Cameras out of step (each scene beside its twin, the same play shot another way):
//   unsync         2 cameras 960x540 or 1280x720 at 60 fps (a third of the rigs: the second at
//                  120 fps), the second started 0.05-4.9 s before the first (both record all the
//                  play; the search runs over +-5 s) at a random phase, drifting up to +-50 ppm,
//                  stamps jittered by up to 0.5 ms, up to 2 % of frames dropped; 10 s of play;
//                  twin: the same rig triggered in step.
//   unsync-webcam  the webcam family's rigs at random offsets and phases; twin: in step.
//   phone          2 phones 1920x1080 at 30 or 60 fps with rolling shutters (each its own
//                  readout, 15-25 ms at 30 fps, 10-16 ms at 60), random offsets and phases; twin:
//                  the same phones with a global shutter.
// Pure: no files, clocks or processes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
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
  // Cameras out of step (`simulate` --start-offsets etc.): per camera start (s; camera 0's is 0),
  // frame rate and drift (ppm); empty: all 0 / fps / 0.
  std::vector<double> start_offsets_s;
  std::vector<int> camera_fps;
  std::vector<double> drift_ppm;
  std::vector<double> rolling_shutter_ms;  // each camera's readout; empty: global shutters
  double drop_rate = 0.0, stamp_jitter_ms = 0.0;
  // The twin measured beside the scene: "in-step" (the same play by cameras triggered together,
  // each at its own rate, the clocks known) or "global-shutter" (the same cameras without rolling
  // shutter); empty: none.
  std::string twin;

  // `p4track simulate` arguments for the scene (without the program and --out).
  std::vector<std::string> SimulateArgs() const;
  // The colour hint `p4track track --ball` takes for this scene's ball.
  std::string TrackBall() const { return ball; }
  nlohmann::ordered_json ToJson() const;
  // The twin scene (precondition: twin is not empty).
  SuiteScene Twin() const;
};

// sports, webcam, white, mono, unsync, unsync-webcam, phone
std::vector<std::string> SuiteFamilies();

// Scene k (1-based) of a family and set. Throws p4::Error for an unknown family or set.
SuiteScene DrawSuiteScene(const std::string& family, const std::string& set, int k);

// Seed of scene k of a set (see above).
uint64_t SuiteSeed(const std::string& set, int k);

// The README's targets of a family (issues "See the ball in any hall", "Cameras that are not in
// step"): per scene (recall, false rows, RMSE, the worst camera's clock error, RMSE over the
// twin's) and over the family's scenes (the median RMSE). A bound at its default does not apply.
struct SuiteTarget {
  double min_recall = 0.0, max_fp = 1.0, max_rmse_mm = 1e9, max_median_rmse_mm = 1e9;
  double max_sync_ms = 1e9;     // the worst camera's clock error at the middle of the play
  double max_twin_ratio = 1e9;  // RMSE over the twin's (the same play in step / global shutter)
};

// Throws p4::Error for an unknown family.
SuiteTarget TargetOf(const std::string& family);

// One scene's figures; a figure the scene does not have is empty (an RMSE with no measured row,
// a sync that was refused or a twin with no RMSE count as missing their targets).
struct SceneFigures {
  bool evaluated = false;  // false: the scene failed before its figures
  std::optional<double> rmse_mm, recall, false_positive_rate, sync_ms, twin_ratio;
};

// How many scenes meet each per-scene target that applies (the others stay 0), and all of them.
struct TargetCounts {
  int scenes = 0;
  int recall = 0, fp = 0, rmse = 0, sync = 0, twin = 0, all = 0;
  // "recall 40, RMSE 41, FP 46, all three 34" for the targets that apply.
  std::string Describe(const SuiteTarget& target) const;
  nlohmann::ordered_json ToJson(const SuiteTarget& target) const;
};
void CountTargetsMet(const SuiteTarget& target, const SceneFigures& scene, TargetCounts* counts);

// Whether a hall's floor has its ball's hue: hues within 25 degrees and the floor's saturation
// over 0.4 (red-brown and brown floors under an orange ball), where the ball's shaded half has
// the floor's colour (docs/DECISIONS.md, "Detection"). Colours RGB in [0, 1].
bool FloorHasBallsHue(const Eigen::Vector3d& floor, const Eigen::Vector3d& ball);

// The groups a scene falls in, for the breakdown of a family's scenes: its cameras, frame rate,
// exposure band (under 1 ms, 1-2, 2-4, 4-10, over 10), ball size band (under 6 px, 6-10, 10-15,
// 15 and over), ball colour and, where known, whether the floor has the ball's hue.
std::vector<std::string> SceneGroups(const SuiteScene& scene, double ball_px,
                                     std::optional<bool> floor_has_balls_hue);

// The ball's diameter in pixels as a scene's cameras see it: per camera the median over the
// truth rows in play with the ball in the picture, then the smallest of the cameras (0 when no
// camera sees it).
double BallPixels(const Rig& rig, const std::vector<TruthRow>& truth);

}  // namespace p4
