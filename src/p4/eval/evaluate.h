// Accuracy of a tracking run against the simulator's ground truth (`p4track eval`).
// Rows are matched by time (the nearest truth row within half a frame) and compared with the
// truth carried ballistically to the row's own time. Pure.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p4/geometry/rig.h"
#include "p4/io/run_files.h"

namespace p4 {

struct EvalOptions {
  double false_positive_mm = 50.0;  // a measured row farther than this from the truth is false
  int min_views = 2;                // recall counts frames seen by this many cameras (or all)
  double gravity = 9.81;            // m/s^2: the truth carried to a row's time between its rows
  // Truth rows whose velocities differ by more than this beyond gravity's (m/s) have a contact
  // (bounce, hit) between them: a row between them is carried from the truth row on its own side
  // of the contact (where the two rows' flights meet), not from the nearer one across it. Drag
  // and spin change the velocity by < 0.3 m/s in a frame of 60 fps.
  double contact_mps = 1.0;
  double min_visible = 0.5;  // with visibility truth: a camera sees the ball from this share
};

struct EvalReport {
  int frames = 0;  // truth rows
  int frames_in_play = 0;
  int frames_seen = 0;  // in play and seen by >= min_views cameras
  int measured_rows = 0;
  int rows = 0;
  double position_rmse_mm = 0.0;  // measured rows while the ball is in play (also the far ones)
  double position_median_mm = 0.0;
  double position_p95_mm = 0.0;
  double position_rmse_all_mm = 0.0;  // every row while the ball is in play
  double recall = 0.0;                // frames_seen with a measured row
  double false_positive_rate = 0.0;   // measured rows far from the truth or with no ball

  nlohmann::ordered_json ToJson() const;
};

// `visibility` (per truth row and camera, the share of the ball seen; may be empty) decides which
// cameras see the ball; without it, a camera sees the ball when it projects inside the image.
EvalReport Evaluate(const std::vector<TruthRow>& truth, const std::vector<TrajectoryRow>& run,
                    const Rig& rig, const std::vector<std::vector<float>>& visibility,
                    const EvalOptions& options = {});

}  // namespace p4
