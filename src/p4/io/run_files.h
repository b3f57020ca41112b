// A tracking run's files (DESIGN.md): trajectory.csv, detections.csv and events.jsonl, appended
// row by row, each frame set's rows in one write (a kill -9 loses at most the moment in hand and
// never tears a row: io/line_appender.h), and score.json replaced atomically after every point;
// and readers for them (eval, replay), which skip an incomplete last line.
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "p4/game/event.h"
#include "p4/geometry/rig.h"
#include "p4/io/line_appender.h"
#include "p4/track/frame_set_tracker.h"

namespace p4 {

class RunWriter {
 public:
  // Creates (truncates) DIR/trajectory.csv, DIR/detections.csv and DIR/events.jsonl; with
  // `resume`, keeps them and checks what is written against what they hold until it runs out
  // (the run made again from its start: LineAppender), score.json left as it is until then.
  // Throws p4::Error.
  RunWriter(const std::string& dir, const Rig& rig, bool resume = false);

  void Write(const track::FrameSetResult& result);
  void WriteEvent(const game::Event& event);
  void WriteScore(const nlohmann::json& score);  // DIR/score.json

  // Resuming: rows found again in the files (0 for a new run).
  int64_t rows_found() const;

 private:
  std::string dir_;
  std::vector<std::string> camera_names_;
  LineAppender trajectory_, detections_, events_;
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
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
};

// The simulator's truth.csv. Throws p4::Error naming the file and line.
std::vector<TruthRow> ReadTruthCsv(const std::string& path);

}  // namespace p4
