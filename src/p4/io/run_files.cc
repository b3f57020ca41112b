#include "p4/io/run_files.h"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "p4/core/error.h"
#include "p4/io/csv.h"
#include "p4/io/event_files.h"

namespace p4 {

RunWriter::RunWriter(const std::string& dir, const Rig& rig) : dir_(dir) {
  for (const auto& c : rig.cameras) camera_names_.push_back(c.name);
  const auto open = [&](std::ofstream& out, const std::string& name, const char* header) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    out.open(path);
    if (!out) throw Error(path + ": cannot create the file");
    out << header << '\n';
    out.flush();
  };
  open(trajectory_, "trajectory.csv", "t,x,y,z,vx,vy,vz,measured,cameras,residual_px");
  open(detections_, "detections.csv", "t,camera,u,v,diameter_px,area_px,accepted");
  const std::string events = (std::filesystem::path(dir) / "events.jsonl").string();
  events_.open(events);
  if (!events_) throw Error(events + ": cannot create the file");
}

void RunWriter::WriteEvent(const game::Event& event) {
  events_ << EventToJsonLine(event) << '\n';
  events_.flush();
}

void RunWriter::WriteScore(const nlohmann::json& score) {
  WriteJson((std::filesystem::path(dir_) / "score.json").string(), score);
}

void RunWriter::Write(const track::FrameSetResult& result) {
  const double t = ToSeconds(result.t);
  for (const auto& d : result.detections) {
    detections_ << fmt::format("{:.6f},{},{:.3f},{:.3f},{:.2f},{},{}\n", t, camera_names_[d.camera],
                               d.observed.x(), d.observed.y(), d.diameter_px, d.area_px,
                               d.accepted ? 1 : 0);
  }
  if (result.state) {
    const auto& s = *result.state;
    trajectory_ << fmt::format("{:.6f},{:.5f},{:.5f},{:.5f},{:.4f},{:.4f},{:.4f},{},{},{:.3f}\n", t,
                               s.position.x(), s.position.y(), s.position.z(), s.velocity.x(),
                               s.velocity.y(), s.velocity.z(), s.measured ? 1 : 0, s.cameras,
                               s.residual_px);
  }
  trajectory_.flush();
  detections_.flush();
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
    row.cameras = static_cast<int>(CsvNumber(path, i, r[8]));
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
