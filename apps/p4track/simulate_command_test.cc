// End-to-end: runs `p4track simulate` and checks what a user would: the videos play with the
// right size, frame count and rate; the truth's projected ball lands on the rendered ball; the
// files are deterministic for a seed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "p4/io/rig_file.h"
#include "p4/io/video_reader.h"
#include "p4track_test_support.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

using testing::P4track;
using testing::Slurp;

struct TruthRow {
  double t;
  Eigen::Vector3d p;
  bool in_play;
};

std::vector<TruthRow> ReadTruth(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,x,y,z,vx,vy,vz,wx,wy,wz,in_play");
  std::vector<TruthRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) f.push_back(cell);
    TruthRow r{std::stod(f[0]), Eigen::Vector3d::Zero(), f.back() == "1"};
    if (r.in_play) r.p = Eigen::Vector3d(std::stod(f[1]), std::stod(f[2]), std::stod(f[3]));
    rows.push_back(r);
  }
  return rows;
}

class SimulateCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("p4_sim_e2e_" + std::to_string(::getpid())));
    // Lossless, short (a serve and a few shots), with lens distortion.
    ASSERT_EQ(P4track("simulate --out " + dir_->string() +
                      " --cameras 2 --size 1280x720 --fps 60 --points 1 --seed 4 --codec ffv1"
                      " --max-duration 3 --distortion"),
              0);
    frames_ = new std::map<std::string, std::vector<I420Image>>();
    times_ = new std::map<std::string, std::vector<TimeNs>>();
    for (const char* name : {"cam0.mkv", "cam1.mkv"}) {
      VideoReader reader((*dir_ / name).string());
      I420Image frame;
      TimeNs pts;
      while (reader.Read(&frame, &pts)) {
        (*frames_)[name].push_back(frame);
        (*times_)[name].push_back(pts);
      }
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete frames_;
    delete times_;
  }
  static fs::path* dir_;
  static std::map<std::string, std::vector<I420Image>>* frames_;  // decoded once
  static std::map<std::string, std::vector<TimeNs>>* times_;
};
fs::path* SimulateCommand::dir_ = nullptr;
std::map<std::string, std::vector<I420Image>>* SimulateCommand::frames_ = nullptr;
std::map<std::string, std::vector<TimeNs>>* SimulateCommand::times_ = nullptr;

TEST_F(SimulateCommand, WritesEveryFile) {
  for (const char* name : {"rig.yaml", "truth.csv", "truth_events.jsonl", "truth_score.json",
                           "cam0.mkv", "cam1.mkv"}) {
    EXPECT_TRUE(fs::exists(*dir_ / name)) << name;
  }
  const Rig rig = ReadRig((*dir_ / "rig.yaml").string());
  EXPECT_EQ(rig.size(), 2);
  const auto events = Slurp((*dir_ / "truth_events.jsonl").string());
  std::stringstream lines(events);
  std::string line;
  std::getline(lines, line);
  const auto first = nlohmann::json::parse(line);
  EXPECT_EQ(first["type"], "serve");
}

TEST_F(SimulateCommand, VideosHaveTheRightSizeFramesAndRate) {
  const auto truth = ReadTruth((*dir_ / "truth.csv").string());
  EXPECT_EQ(truth.size(), 180u);  // 3 s at 60 fps
  for (const char* name : {"cam0.mkv", "cam1.mkv"}) {
    VideoReader reader((*dir_ / name).string());
    EXPECT_EQ(reader.info().width, 1280);
    EXPECT_EQ(reader.info().height, 720);
    EXPECT_NEAR(reader.info().fps, 60.0, 1e-6);
    const auto& times = (*times_)[name];
    ASSERT_EQ(times.size(), 180u) << name;
    for (std::size_t n = 0; n < times.size(); ++n) EXPECT_NEAR(ToSeconds(times[n]), n / 60.0, 1e-3);
  }
}

// Where the ball was rendered: the luma difference to the same pixels in frames 0.5 s earlier
// and later (when those two agree, they show the background), weighted centroid in a window
// around the projection of the truth. Frames with the ball over the table, away from the net and
// slow enough that motion blur stays under ~2 px.
TEST_F(SimulateCommand, ProjectedTruthLandsOnTheRenderedBall) {
  const Rig rig = ReadRig((*dir_ / "rig.yaml").string());
  const auto truth = ReadTruth((*dir_ / "truth.csv").string());
  int checked = 0;
  double worst = 0.0, sum = 0.0;
  for (const Camera& camera : rig.cameras) {
    const auto& frames = (*frames_)[camera.name + ".mkv"];
    ASSERT_EQ(frames.size(), truth.size());
    const int w = camera.width;
    for (std::size_t k = 30; k + 31 < truth.size(); ++k) {
      const TruthRow& row = truth[k];
      if (!row.in_play || !truth[k - 1].in_play || !truth[k + 1].in_play) continue;
      if (std::abs(row.p.x()) > 1.2 || std::abs(row.p.x()) < 0.15 || std::abs(row.p.y()) > 0.6 ||
          row.p.z() < 0.03) {
        continue;
      }
      // Not seen through or past the top of the net (its white band hides part of the ball).
      const Eigen::Vector3d eye = camera.Center();
      if ((eye.x() < 0) != (row.p.x() < 0)) {
        const double s = eye.x() / (eye.x() - row.p.x());
        if (eye.z() + s * (row.p.z() - eye.z()) < 0.1525 + 0.06) continue;
      }
      const auto px = camera.Project(row.p);
      const auto before = camera.Project(truth[k - 1].p), after = camera.Project(truth[k + 1].p);
      if (!px || !before || !after || !camera.InImage(*px, 16.0)) continue;
      // Blur over the 2 ms exposure (1/16 of the two frames between before and after) < 2 px.
      if ((*after - *before).norm() > 30.0) continue;
      const int cx = static_cast<int>(std::lround(px->x())),
                cy = static_cast<int>(std::lround(px->y()));
      const int half = 8;
      const auto& a = frames[k - 30];
      const auto& b = frames[k + 30];
      double background_change = 0.0;
      for (int y = cy - half; y <= cy + half; ++y) {
        for (int x = cx - half; x <= cx + half; ++x) {
          background_change += std::abs(a.y()[y * w + x] - b.y()[y * w + x]);
        }
      }
      if (background_change / ((2 * half + 1) * (2 * half + 1)) > 4.0) continue;  // not clean
      double sw = 0.0, sx = 0.0, sy = 0.0;
      for (int y = cy - half; y <= cy + half; ++y) {
        for (int x = cx - half; x <= cx + half; ++x) {
          const double bg = 0.5 * (a.y()[y * w + x] + b.y()[y * w + x]);
          const double d = std::abs(frames[k].y()[y * w + x] - bg);
          if (d < 12.0) continue;  // noise (sigma 2 per frame)
          sw += d, sx += d * x, sy += d * y;
        }
      }
      if (sw < 300.0) continue;  // hidden (net, player) or too small
      const double error = (Eigen::Vector2d(sx / sw, sy / sw) - *px).norm();
      worst = std::max(worst, error);
      sum += error;
      EXPECT_LT(error, 0.5) << camera.name << " frame " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 15);
  std::printf("checked %d ball images, mean centroid error %.3f px, worst %.3f px\n", checked,
              checked ? sum / checked : 0.0, worst);
}

TEST_F(SimulateCommand, SameSeedSameTruthBytes) {
  const fs::path again = *dir_ / "again";
  ASSERT_EQ(P4track("simulate --out " + again.string() +
                    " --cameras 1 --size 320x180 --fps 60 --points 1 --seed 4 --max-duration 3"),
            0);
  for (const char* name : {"truth.csv", "truth_events.jsonl", "truth_score.json"}) {
    EXPECT_EQ(Slurp((*dir_ / name).string()), Slurp((again / name).string())) << name;
  }
  // The H.264 video as ffprobe sees it: size, rate and the number of decoded frames.
  const std::string probe = (again / "probe.txt").string();
  ASSERT_EQ(std::system(("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                         "stream=codec_name,width,height,r_frame_rate,nb_read_frames -of csv=p=0 " +
                         (again / "cam0.mp4").string() + " > " + probe)
                            .c_str()),
            0);
  EXPECT_EQ(Slurp(probe), "h264,320,180,60/1,180\n");
}

TEST_F(SimulateCommand, BadOptionsFailWithAMessage) {
  EXPECT_NE(P4track("simulate --out /tmp/p4_bad --size 640by480"), 0);
  EXPECT_NE(P4track("simulate --out /tmp/p4_bad --best-of 4"), 0);
  EXPECT_NE(P4track("simulate"), 0);  // --out is required
  // A readout per camera, each within its frame.
  EXPECT_NE(P4track("simulate --out /tmp/p4_bad --cameras 2 --rolling-shutter-ms 12,18,3"), 0);
  EXPECT_NE(P4track("simulate --out /tmp/p4_bad --fps 60 --rolling-shutter-ms 18"), 0);
  EXPECT_NE(P4track("simulate --out /tmp/p4_bad --rolling-shutter-ms 12,x"), 0);
}

}  // namespace
}  // namespace p4
