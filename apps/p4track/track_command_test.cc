// End-to-end: simulate a short match (the simulator's defaults: 2 cameras, 1280x720, 120 fps,
// orange ball, H.264), track it from the videos, evaluate against the truth; and the errors a
// user meets with bad input.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "p4/io/test_damage.h"
#include "p4track_test_support.h"

namespace {

namespace fs = std::filesystem;

using p4::testing::EvalReport;
using p4::testing::P4track;
using p4::testing::Slurp;

class TrackCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("p4_track_e2e_" + std::to_string(::getpid())));
    sim_ = *dir_ / "sim";
    run_ = *dir_ / "run";
    ASSERT_EQ(P4track("simulate --out " + sim_.string() + " --points 2 --seed 22 --max-duration 8"),
              0);
    ASSERT_EQ(P4track("track --rig " + (sim_ / "rig.yaml").string() + " --out " + run_.string() +
                      " " + (sim_ / "cam0.mp4").string() + " " + (sim_ / "cam1.mp4").string()),
              0);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path* dir_;
  static fs::path sim_, run_;
};
fs::path* TrackCommand::dir_ = nullptr;
fs::path TrackCommand::sim_;
fs::path TrackCommand::run_;

TEST_F(TrackCommand, MeetsTheAccuracyTargets) {
  const auto report = EvalReport(sim_, run_);
  std::printf("%s\n", report.dump().c_str());
  EXPECT_GT(report["frames_seen"].get<int>(), 500);
  EXPECT_LE(report["position_rmse_mm"].get<double>(), 5.0);
  EXPECT_GE(report["recall"].get<double>(), 0.99);
  EXPECT_LE(report["false_positive_rate"].get<double>(), 0.005);
  EXPECT_LE(report["position_rmse_all_mm"].get<double>(), 100.0);
}

// The single-camera fallback on the simulator's defaults but one camera: the target is 50 mm
// on measured rows. The stroke smoother (bearings, diameters, table contacts) must also beat the
// Kalman filter's own one-camera rows by far.
class OneCamera : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ =
        new fs::path(fs::temp_directory_path() / ("p4_track_e2e1_" + std::to_string(::getpid())));
    sim_ = *dir_ / "sim";
    ASSERT_EQ(P4track("simulate --cameras 1 --out " + sim_.string() +
                      " --points 2 --seed 22 --max-duration 8"),
              0);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static nlohmann::json TrackAndEvaluate(const std::string& name, const std::string& flags) {
    const fs::path run = *dir_ / name;
    EXPECT_EQ(P4track("track --rig " + (sim_ / "rig.yaml").string() + " --out " + run.string() +
                      " " + (sim_ / "cam0.mp4").string() + flags),
              0);
    return EvalReport(sim_, run);
  }
  static fs::path* dir_;
  static fs::path sim_;
};
fs::path* OneCamera::dir_ = nullptr;
fs::path OneCamera::sim_;

TEST_F(OneCamera, MeetsTheSingleCameraTarget) {
  const auto smoothed = TrackAndEvaluate("run", "");
  const auto filtered = TrackAndEvaluate("filter", " --no-smoothing");
  std::printf("smoothed: %s\nfilter only: %s\n", smoothed.dump().c_str(), filtered.dump().c_str());
  EXPECT_GT(smoothed["measured_rows"].get<int>(), 600);
  EXPECT_LE(smoothed["position_rmse_mm"].get<double>(), 50.0);
  // 0 % on this scene before the hall's look grew richer (shoes, a sensor that clips); since
  // then one service toss is fitted up to 13 cm off in depth (6 % of the rows): see README
  // "Measured on many worlds" for the one-camera family, whose target is not met yet.
  EXPECT_LE(smoothed["false_positive_rate"].get<double>(), 0.08);
  EXPECT_GE(smoothed["bounce_recall"].get<double>(), 0.8);
  EXPECT_LT(2.0 * smoothed["position_rmse_mm"].get<double>(),
            filtered["position_rmse_mm"].get<double>());
}

TEST_F(TrackCommand, WritesTheRunFilesAsDesigned) {
  std::ifstream trajectory(run_ / "trajectory.csv");
  std::string line;
  std::getline(trajectory, line);
  EXPECT_EQ(line, "t,x,y,z,vx,vy,vz,measured,cameras,residual_px");
  int rows = 0, measured = 0;
  while (std::getline(trajectory, line)) {
    ++rows;
    measured += line.find(",1,2,") != std::string::npos;
  }
  EXPECT_GT(rows, 500);
  EXPECT_GT(measured, 400);
  std::ifstream detections(run_ / "detections.csv");
  std::getline(detections, line);
  EXPECT_EQ(line, "t,camera,u,v,diameter_px,area_px,accepted");
  std::getline(detections, line);
  EXPECT_TRUE(line.find(",cam0,") != std::string::npos || line.find(",cam1,") != std::string::npos)
      << line;
}

// 20 KB of bad bytes in the middle of one camera's recording: the frames the decoder cannot make
// are skipped and reported (once, with where and how many), the rest are tracked to the end.
TEST_F(TrackCommand, ADamagedRecordingLosesOnlyTheDamagedFrames) {
  const fs::path damaged = *dir_ / "damaged_cam0.mp4";
  fs::copy_file(sim_ / "cam0.mp4", damaged, fs::copy_options::overwrite_existing);
  p4::testing::OverwriteWithNoise(
      damaged.string(), static_cast<std::streamoff>(fs::file_size(damaged) * 6 / 10), 20'000);
  const fs::path run = *dir_ / "run_damaged";
  std::string out;
  ASSERT_EQ(P4track("track --rig " + (run_ / "rig_synced.yaml").string() + " --classes " +
                        (run_ / "ball_classes.yaml").string() + " --out " + run.string() + " " +
                        damaged.string() + " " + (sim_ / "cam1.mp4").string(),
                    &out),
            0)
      << out;
  std::size_t at = out.find("damaged data skipped");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(out.find("damaged data skipped", at + 1), std::string::npos) << "one gap, said once";
  EXPECT_NE(out.find("damaged frame(s) skipped in 1 stretch"), std::string::npos) << out;
  const auto report = EvalReport(sim_, run);
  const auto clean = EvalReport(sim_, run_);
  std::printf("damaged: %s\n", report.dump().c_str());
  EXPECT_GE(report["recall"].get<double>(), clean["recall"].get<double>() - 0.03);
  EXPECT_LE(report["position_rmse_mm"].get<double>(), 5.0);
  EXPECT_LE(report["false_positive_rate"].get<double>(), 0.005);
  EXPECT_EQ(report["final_score_right"], clean["final_score_right"]);
}

// kill -9 in the middle of a run, then `track --resume`: the folder reads back as it was left (no
// torn row, score.json whole), and the resumed run's files are those of the run that was never
// stopped, byte for byte (the same rows, events and score). The killed run is paced at the
// video's own rate (--realtime) so that it is surely under way when killed; the test waits on
// its rows, not on a clock.
TEST_F(TrackCommand, AKilledRunResumesToTheUninterruptedResult) {
  const fs::path run = *dir_ / "run_killed";
  const fs::path log = *dir_ / "killed.log";
  const pid_t pid = p4::testing::StartP4track(
      "track --realtime --rig " + (sim_ / "rig.yaml").string() + " --out " + run.string() + " " +
          (sim_ / "cam0.mp4").string() + " " + (sim_ / "cam1.mp4").string(),
      log);
  ASSERT_GT(pid, 0);
  int status = 0;
  bool exited = false;
  while (p4::testing::CountLines(run / "trajectory.csv") < 200) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    ::usleep(5'000);
  }
  ASSERT_FALSE(exited) << "the run ended before it could be killed: " << Slurp(log);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  const int rows_left = p4::testing::CountLines(run / "trajectory.csv");
  EXPECT_LT(rows_left, p4::testing::CountLines(run_ / "trajectory.csv"));
  // What the kill left reads back (eval reads trajectory.csv and events.jsonl).
  EvalReport(sim_, run);
  std::string out;
  ASSERT_EQ(P4track("track --resume " + run.string(), &out), 0) << out;
  EXPECT_NE(out.find("resumed: "), std::string::npos) << out;
  for (const char* file : {"trajectory.csv", "detections.csv", "events.jsonl", "score.json"}) {
    EXPECT_EQ(Slurp(run / file), Slurp(run_ / file)) << file << " differs after the resume";
  }
  // A finished run has nothing to resume.
  ASSERT_EQ(P4track("track --resume " + run.string(), &out), 0) << out;
  EXPECT_NE(out.find("nothing to resume"), std::string::npos) << out;
}

// The game layer end to end: events from the track, the referee's points and score.
TEST_F(TrackCommand, TheRefereeScoresTheSimulatedPoints) {
  const auto report = EvalReport(sim_, run_);
  EXPECT_GE(report["bounces_truth"].get<int>(), 5);
  EXPECT_GE(report["bounce_recall"].get<double>(), 0.99);
  EXPECT_GE(report["bounce_precision"].get<double>(), 0.99);
  EXPECT_LE(report["bounce_position_median_mm"].get<double>(), 5.0);
  EXPECT_LE(report["bounce_time_median_ms"].get<double>(), 5.0);
  const int points = report["points_truth"].get<int>();  // the 8 s scene holds one
  EXPECT_GE(points, 1);
  EXPECT_EQ(report["points_run"].get<int>(), points);
  EXPECT_DOUBLE_EQ(report["point_winner_share"].get<double>(), 1.0);
  EXPECT_TRUE(report["final_score_right"].get<bool>());
  // score.json as DESIGN.md describes it, and point events with the running score.
  const auto score = nlohmann::json::parse(Slurp(run_ / "score.json"));
  EXPECT_EQ(score["points_played"].get<int>(), points);
  EXPECT_EQ(score["players"][0].get<std::string>(), "A");
  const std::string events = Slurp(run_ / "events.jsonl");
  EXPECT_NE(events.find("\"type\":\"bounce\",\"side\":"), std::string::npos);
  EXPECT_NE(events.find("\"type\":\"point\",\"winner\":"), std::string::npos);
  EXPECT_NE(events.find("\"type\":\"serve\",\"player\":\"A\""), std::string::npos);
}

TEST_F(TrackCommand, BadInputGetsAClearMessage) {
  const std::string rig = (sim_ / "rig.yaml").string();
  const std::string cam0 = (sim_ / "cam0.mp4").string();
  const std::string out = (*dir_ / "bad").string();
  std::string msg;
  // A missing video.
  EXPECT_NE(
      P4track("track --rig " + rig + " --out " + out + " " + cam0 + " /nonexistent/cam1.mp4", &msg),
      0);
  EXPECT_NE(msg.find("/nonexistent/cam1.mp4"), std::string::npos) << msg;
  // An unreadable video (not a video at all).
  const fs::path junk = *dir_ / "junk.mp4";
  std::ofstream(junk) << "not a video";
  EXPECT_NE(
      P4track("track --rig " + rig + " --out " + out + " " + cam0 + " " + junk.string(), &msg), 0);
  EXPECT_NE(msg.find("junk.mp4"), std::string::npos) << msg;
  // Markers to show, but no live view to show them in.
  EXPECT_EQ(
      P4track("track --rig " + rig + " --out " + out + " --layout " + rig + " " + cam0 + " " + cam0,
              &msg),
      2);
  EXPECT_NE(msg.find("shown by the live view only (add --ui)"), std::string::npos) << msg;
  // Camera count.
  EXPECT_NE(P4track("track --rig " + rig + " --out " + out + " " + cam0, &msg), 0);
  EXPECT_NE(msg.find("2 camera(s) but 1 source(s)"), std::string::npos) << msg;
  // Image size.
  const fs::path small = *dir_ / "small";
  ASSERT_EQ(
      P4track("simulate --out " + small.string() + " --size 320x180 --points 1 --max-duration 0.1"),
      0);
  EXPECT_NE(P4track("track --rig " + rig + " --out " + out + " " + cam0 + " " +
                        (small / "cam1.mp4").string(),
                    &msg),
            0);
  EXPECT_NE(msg.find("320x180"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1280x720"), std::string::npos) << msg;
  // Empty and corrupt colour-class files.
  const fs::path empty = *dir_ / "empty.yaml";
  std::ofstream(empty).flush();
  EXPECT_NE(P4track("track --rig " + rig + " --out " + out + " --classes " + empty.string() + " " +
                        cam0 + " " + cam0,
                    &msg),
            0);
  EXPECT_NE(msg.find("empty.yaml: the file is empty"), std::string::npos) << msg;
  const fs::path corrupt = *dir_ / "corrupt.yaml";
  std::ofstream(corrupt)
      << "%YAML:1.0\n---\nclasses:\n  - { name: ball_a, y: [10, 300], u: [0, 255], v: [0, 255] }\n";
  EXPECT_NE(P4track("track --rig " + rig + " --out " + out + " --classes " + corrupt.string() +
                        " " + cam0 + " " + cam0,
                    &msg),
            0);
  EXPECT_NE(msg.find("corrupt.yaml: classes[0] 'ball_a': y: 300 is outside 0-255"),
            std::string::npos)
      << msg;
}

}  // namespace
