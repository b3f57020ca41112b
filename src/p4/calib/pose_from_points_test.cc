#include "p4/calib/pose_from_points.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "p4/core/table.h"
#include "p4/geometry/test_cameras.h"

namespace p4::calib {
namespace {

// The table features `calibrate table` uses: 4 corners of the playing surface, 2 net-post tops.
std::vector<Eigen::Vector3d> TableFeatures() {
  const double hx = 0.5 * table::kLength, hy = 0.5 * table::kWidth;
  return {{-hx, hy, 0.0},  {hx, hy, 0.0},         {hx, -hy, 0.0},
          {-hx, -hy, 0.0}, {0.0, -0.915, 0.1525}, {0.0, 0.915, 0.1525}};
}

std::vector<PointMatch> Observe(const Camera& camera, const std::vector<Eigen::Vector3d>& world,
                                double noise_px, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_px);
  std::vector<PointMatch> points;
  for (const auto& w : world) {
    const Eigen::Vector2d px = camera.Project(w).value();
    points.push_back({px + Eigen::Vector2d(noise(rng), noise(rng)), w});
  }
  return points;
}

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

TEST(SolvePose, RecoversAKnownCameraFromTableFeatures) {
  for (const Camera& truth : testing::ClubCameras()) {
    std::string error;
    const auto fit = SolvePose(truth, Observe(truth, TableFeatures(), 0.0), &error);
    ASSERT_TRUE(fit) << truth.name << ": " << error;
    EXPECT_LT((fit->camera.Center() - truth.Center()).norm(), 1e-6) << truth.name;
    EXPECT_LT(AngleDeg(fit->camera.cam_from_world.rotation, truth.cam_from_world.rotation), 1e-6);
    EXPECT_LT(fit->rms_px, 1e-6);
  }
}

TEST(SolvePoseAndFocal, EstimatesTheFocalLengthOfAnUnknownCamera) {
  for (Camera truth : testing::ClubCameras()) {
    truth.distortion.fill(0.0);
    truth.fy = truth.fx;
    truth.cx = 0.5 * (truth.width - 1);
    truth.cy = 0.5 * (truth.height - 1);
    std::string error;
    // Exact points: exact answer.
    auto fit = SolvePoseAndFocal(truth.name, truth.width, truth.height,
                                 Observe(truth, TableFeatures(), 0.0), &error);
    ASSERT_TRUE(fit) << truth.name << ": " << error;
    EXPECT_NEAR(fit->camera.fx, truth.fx, 1e-3 * truth.fx) << truth.name;
    EXPECT_LT((fit->camera.Center() - truth.Center()).norm(), 0.002) << truth.name;
    // Clicked points (1 px of noise): the focal length within a few percent, the pose within
    // centimetres, and the error reported is the noise's size.
    fit = SolvePoseAndFocal(truth.name, truth.width, truth.height,
                            Observe(truth, TableFeatures(), 1.0, 7), &error);
    ASSERT_TRUE(fit) << truth.name << ": " << error;
    EXPECT_NEAR(fit->camera.fx, truth.fx, 0.05 * truth.fx) << truth.name;
    EXPECT_LT((fit->camera.Center() - truth.Center()).norm(), 0.25) << truth.name;
    EXPECT_GT(fit->rms_px, 0.1);
    EXPECT_LT(fit->rms_px, 2.0);
  }
}

TEST(SolvePose, RefusesTooFewOrDegeneratePoints) {
  const Camera camera = testing::ClubCameras()[0];
  std::string error;
  auto points = Observe(camera, TableFeatures(), 0.0);
  points.resize(3);
  EXPECT_FALSE(SolvePose(camera, points, &error));
  EXPECT_EQ(error, "3 point(s), at least 4 needed");
  // Four points along the table's long edge: on one line.
  const auto line =
      Observe(camera, {{-1.0, 0.7, 0.0}, {0.0, 0.7, 0.0}, {0.5, 0.7, 0.0}, {1.2, 0.7, 0.0}}, 0.0);
  EXPECT_FALSE(SolvePose(camera, line, &error));
  EXPECT_EQ(error, "the world points lie on one line");
  EXPECT_FALSE(SolvePoseAndFocal("x", 1280, 720, line, &error));
  EXPECT_EQ(error, "the world points lie on one line");
  EXPECT_FALSE(SolvePoseAndFocal("x", 0, 720, Observe(camera, TableFeatures(), 0.0), &error));
}

}  // namespace
}  // namespace p4::calib
