// A tracking run's files (DESIGN.md): trajectory.csv and detections.csv, appended and flushed
// row by row so that a crash loses at most the last moment; and readers for them (eval).
#pragma once

#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "p4/geometry/rig.h"
#include "p4/track/frame_set_tracker.h"

namespace p4 {

class RunWriter {
 public:
  // Creates (truncates) DIR/trajectory.csv and DIR/detections.csv. Throws p4::Error.
  RunWriter(const std::string& dir, const Rig& rig);

  void Write(const track::FrameSetResult& result);

 private:
  std::vector<std::string> camera_names_;
  std::ofstream trajectory_, detections_;
};

struct TrajectoryRow {
  double t = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  bool measured = false;
  int cameras = 0;
  double residual_px = 0.0;
};

// trajectory.csv as written above. Throws p4::Error naming the file and line.
std::vector<TrajectoryRow> ReadTrajectoryCsv(const std::string& path);

struct TruthRow {
  double t = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool in_play = false;
};

// The simulator's truth.csv. Throws p4::Error naming the file and line.
std::vector<TruthRow> ReadTruthCsv(const std::string& path);

}  // namespace p4
