// End-to-end: `calibrate rig` on a simulated scene with ArUco markers on the table corners
// (2 cameras, 1280x720, H.264), compared with the true rig and by tracking with either;
// `calibrate intrinsics` and `calibrate table` on the real data; the errors a user meets.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "p4/io/rig_file.h"
#include "p4track_test_support.h"

namespace {

namespace fs = std::filesystem;

using p4::testing::P4track;
using p4::testing::Slurp;

const std::string kData = P4_SHARED_DATA;

class CalibrateCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("p4_calib_e2e_" + std::to_string(::getpid())));
    sim_ = *dir_ / "sim";
    ASSERT_EQ(P4track("simulate --markers --out " + sim_.string() +
                      " --points 2 --seed 22 --max-duration 8"),
              0);
    const std::string videos = (sim_ / "cam0.mp4").string() + " " + (sim_ / "cam1.mp4").string();
    std::string out;
    // The intrinsics are the rig's (as `calibrate intrinsics` would give them); the poses are
    // found from the markers in the first 10 frames of each video.
    ASSERT_EQ(P4track("calibrate rig --layout " + (sim_ / "markers.yaml").string() +
                          " --intrinsics " + (sim_ / "rig.yaml").string() + " --out " +
                          (*dir_ / "calibrated.yaml").string() + " " + videos,
                      &out),
              0)
        << out;
    std::printf("%s", out.c_str());
    for (const std::string rig : {"rig", "calibrated"}) {
      const std::string rig_path =
          rig == "rig" ? (sim_ / "rig.yaml").string() : (*dir_ / "calibrated.yaml").string();
      ASSERT_EQ(P4track("track --rig " + rig_path + " --out " + (*dir_ / ("run_" + rig)).string() +
                        " " + videos),
                0);
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static nlohmann::json Eval(const std::string& run) {
    return p4::testing::EvalReport(sim_, *dir_ / run);
  }
  static fs::path* dir_;
  static fs::path sim_;
};
fs::path* CalibrateCommand::dir_ = nullptr;
fs::path CalibrateCommand::sim_;

TEST_F(CalibrateCommand, MarkersGiveTheTrueRigToMillimetres) {
  const p4::Rig truth = p4::ReadRig((sim_ / "rig.yaml").string());
  const p4::Rig calibrated = p4::ReadRig((*dir_ / "calibrated.yaml").string());
  ASSERT_EQ(calibrated.size(), truth.size());
  for (int c = 0; c < truth.size(); ++c) {
    const auto& t = truth.cameras[c];
    const auto& k = calibrated.cameras[c];
    EXPECT_EQ(k.name, t.name);
    const double centre_mm = 1000.0 * (k.Center() - t.Center()).norm();
    const double angle_deg =
        Eigen::AngleAxisd(k.cam_from_world.rotation.transpose() * t.cam_from_world.rotation)
            .angle() *
        180.0 / M_PI;
    std::printf("%s: centre %.2f mm, rotation %.4f deg\n", t.name.c_str(), centre_mm, angle_deg);
    EXPECT_LT(centre_mm, 5.0);
    EXPECT_LT(angle_deg, 0.1);
  }
  // The calibration's error is written beside each camera.
  EXPECT_NE(Slurp(*dir_ / "calibrated.yaml").find("reprojection_error_px"), std::string::npos);
}

TEST_F(CalibrateCommand, TrackingWithTheCalibratedRigIsAsAccurate) {
  const auto truth_rig = Eval("run_rig");
  const auto calibrated = Eval("run_calibrated");
  const double a = truth_rig["position_rmse_mm"].get<double>();
  const double b = calibrated["position_rmse_mm"].get<double>();
  std::printf("RMSE with the true rig %.3f mm, with the calibrated rig %.3f mm\n", a, b);
  EXPECT_LT(std::abs(b - a), 1.0);
  EXPECT_GE(calibrated["recall"].get<double>(), 0.99);
}

TEST_F(CalibrateCommand, RefusesACameraThatSeesNoMarkerOfTheLayout) {
  const fs::path layout = *dir_ / "other.yaml";
  std::ofstream(layout) << "%YAML:1.0\n---\nmarkers:\n"
                           "  - { id: 30, corners: [[0,0,0],[0.1,0,0],[0.1,0.1,0],[0,0.1,0]] }\n";
  std::string out;
  EXPECT_EQ(P4track("calibrate rig --layout " + layout.string() + " --out " +
                        (*dir_ / "never.yaml").string() + " " + (sim_ / "cam0.mp4").string(),
                    &out),
            2);
  EXPECT_NE(out.find("cam0"), std::string::npos) << out;
  EXPECT_NE(out.find("sees 0 marker(s) of the layout, 1 needed (found ids not in the layout: 0 "),
            std::string::npos)
      << out;
  EXPECT_FALSE(fs::exists(*dir_ / "never.yaml"));
}

TEST_F(CalibrateCommand, IntrinsicsFromOpenCvsChessboardImages) {
  const fs::path rig = *dir_ / "left.yaml";
  std::string out;
  ASSERT_EQ(P4track("calibrate intrinsics --fix-aspect --name left --out " + rig.string() + " '" +
                        kData + "/calibration/opencv_stereo_chessboard/left*.jpg'",
                    &out),
            0)
      << out;
  EXPECT_NE(out.find("dropped left02.jpg"), std::string::npos) << out;
  const p4::Rig r = p4::ReadRig(rig.string());
  ASSERT_EQ(r.size(), 1);
  EXPECT_NEAR(r.cameras[0].fx, 536.0, 6.0);  // OpenCV's 535.9 with all 13 views
  // Too few images with the board: refused, with the reason.
  EXPECT_EQ(P4track("calibrate intrinsics --out " + (*dir_ / "no.yaml").string() + " '" + kData +
                        "/calibration/opencv_stereo_chessboard/left0[12].jpg'",
                    &out),
            2);
  EXPECT_NE(out.find("the board was found in 2 image(s), at least 8 needed"), std::string::npos)
      << out;
}

TEST_F(CalibrateCommand, TableFromTheRealPhonesPoints) {
  const std::string phones = kData + "/detections/two_phones_30fps/";
  const fs::path rig = *dir_ / "phones.yaml";
  std::string out;
  ASSERT_EQ(
      P4track("calibrate table --size 1280x720 --out " + rig.string() + " --points " + phones +
                  "cam0_table_points.csv --points " + phones + "cam1_table_points.csv",
              &out),
      0)
      << out;
  EXPECT_NE(out.find("(focal length estimated)"), std::string::npos) << out;
  const p4::Rig r = p4::ReadRig(rig.string());
  ASSERT_EQ(r.size(), 2);
  // The phones stand at the two long sides of the table, 3-4 m away.
  EXPECT_LT(r.cameras[0].Center().y(), -2.5);
  EXPECT_GT(r.cameras[1].Center().y(), 2.5);
  // Three points on one line: refused.
  const fs::path line = *dir_ / "line.csv";
  std::ofstream(line) << "u,v,x,y,z\n100,100,0,0,0\n200,100,1,0,0\n300,100,2,0,0\n400,100,3,0,0\n";
  EXPECT_EQ(P4track("calibrate table --out " + (*dir_ / "no.yaml").string() + " --points " +
                        line.string(),
                    &out),
            2);
  EXPECT_NE(out.find("the world points lie on one line"), std::string::npos) << out;
}

}  // namespace
