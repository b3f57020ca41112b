#include "p4/io/run_files.h"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "p4/core/error.h"
#include "p4/io/csv.h"
#include "p4/io/event_files.h"

namespace p4 {

namespace {
std::string In(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
}
}  // namespace

RunWriter::RunWriter(const std::string& dir, const Rig& rig, bool resume)
    : dir_(dir),
      trajectory_(In(dir, "trajectory.csv"), resume),
      detections_(In(dir, "detections.csv"), resume),
      events_(In(dir, "events.jsonl"), resume) {
  for (const auto& c : rig.cameras) camera_names_.push_back(c.name);
  trajectory_.Append("t,x,y,z,vx,vy,vz,measured,cameras,residual_px\n");
  detections_.Append("t,camera,u,v,diameter_px,area_px,accepted\n");
}

int64_t RunWriter::rows_found() const {
  return trajectory_.lines_found() + detections_.lines_found() + events_.lines_found();
}

void RunWriter::WriteEvent(const game::Event& event) {
  events_.Append(EventToJsonLine(event) + '\n');
}

void RunWriter::WriteScore(const nlohmann::json& score) {
  // Resuming: the score of a point already in the files is older than the one there.
  if (!events_.caught_up()) return;
  WriteJson(In(dir_, "score.json"), score);
}

void RunWriter::Write(const track::FrameSetResult& result) {
  const double t = ToSeconds(result.t);
  std::string lines;
  for (const auto& d : result.detections) {
    lines +=
        fmt::format("{:.6f},{},{:.3f},{:.3f},{:.2f},{},{}\n", t, camera_names_[d.camera],
                    d.observed.x(), d.observed.y(), d.diameter_px, d.area_px, d.accepted ? 1 : 0);
  }
  if (!lines.empty()) detections_.Append(lines);
  if (result.state) {
    const auto& s = *result.state;
    trajectory_.Append(
        fmt::format("{:.6f},{:.5f},{:.5f},{:.5f},{:.4f},{:.4f},{:.4f},{},{},{:.3f}\n", t,
                    s.position.x(), s.position.y(), s.position.z(), s.velocity.x(), s.velocity.y(),
                    s.velocity.z(), s.measured ? 1 : 0, s.cameras, s.residual_px));
  }
}

std::vector<TrajectoryRow> ReadTrajectoryCsv(const std::string& path) {
  const auto rows = ReadCsv(path, "t,x,y,z,vx,vy,vz,measured,cameras,residual_px");
  std::vector<TrajectoryRow> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    TrajectoryRow row;
    row.t = CsvNumber(path, i, r[0]);
    row.position = {CsvNumber(path, i, r[1]), CsvNumber(path, i, r[2]), CsvNumber(path, i, r[3])};
    row.velocity = {CsvNumber(path, i, r[4]), CsvNumber(path, i, r[5]), CsvNumber(path, i, r[6])};
    row.measured = CsvNumber(path, i, r[7]) != 0.0;
    row.cameras = CsvInt(path, i, r[8], 0, 1024);
    row.residual_px = CsvNumber(path, i, r[9]);
    out.push_back(row);
  }
  return out;
}

std::vector<TruthRow> ReadTruthCsv(const std::string& path) {
  const auto rows = ReadCsv(path, "t,x,y,z,vx,vy,vz,wx,wy,wz,in_play");
  std::vector<TruthRow> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    TruthRow row;
    row.t = CsvNumber(path, i, r[0]);
    row.in_play = r[10] == "1";
    if (row.in_play) {
      row.position = {CsvNumber(path, i, r[1]), CsvNumber(path, i, r[2]), CsvNumber(path, i, r[3])};
      row.velocity = {CsvNumber(path, i, r[4]), CsvNumber(path, i, r[5]), CsvNumber(path, i, r[6])};
    }
    out.push_back(row);
  }
  return out;
}

}  // namespace p4
