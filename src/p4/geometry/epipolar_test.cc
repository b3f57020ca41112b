#include "p4/geometry/epipolar.h"

#include <gtest/gtest.h>

#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

TEST(Epipolar, TrueCorrespondenceLiesOnTheLine) {
  const auto cameras = testing::ClubCameras();  // camera 1 has lens distortion
  for (const Eigen::Vector3d& point :
       {Eigen::Vector3d(0.5, 0.2, 0.3), Eigen::Vector3d(-1.1, -0.6, 0.02),
        Eigen::Vector3d(1.5, 0.7, 0.8)}) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (i == j) continue;
        const auto pi = cameras[i].Project(point);
        const auto pj = cameras[j].Project(point);
        ASSERT_TRUE(pi && pj);
        EXPECT_NEAR(EpipolarDistance(cameras[i], *pi, cameras[j], *pj), 0.0, 1e-6)
            << i << "->" << j;
      }
    }
  }
}

TEST(Epipolar, DistanceGrowsWithAnOffsetAcrossTheLine) {
  const auto cameras = testing::ClubCameras();
  const Eigen::Vector3d point(0.4, 0.1, 0.2);
  const auto p0 = cameras[0].Project(point);
  const auto p2 = cameras[2].Project(point);
  const Eigen::Vector3d line = EpipolarLine(cameras[0], *p0, cameras[2]);
  EXPECT_NEAR(line.head<2>().norm(), 1.0, 1e-12);
  const Eigen::Vector2d across = line.head<2>();  // the line's normal
  EXPECT_NEAR(EpipolarDistance(cameras[0], *p0, cameras[2], *p2 + 5.0 * across), 5.0, 1e-6);
  const Eigen::Vector2d along(-across.y(), across.x());
  EXPECT_NEAR(EpipolarDistance(cameras[0], *p0, cameras[2], *p2 + 30.0 * along), 0.0, 1e-6);
}

TEST(Epipolar, CurvePassesThroughTheProjection) {
  const auto cameras = testing::ClubCameras();
  const Eigen::Vector3d point(0.4, 0.1, 0.2);
  const auto p0 = cameras[0].Project(point);
  const auto p1 = cameras[1].Project(point);  // distorted camera: the "line" is a curve
  const auto curve = EpipolarCurve(cameras[0], *p0, cameras[1], 2.0, 6.0, 4000);
  ASSERT_GT(curve.size(), 100u);
  double best = 1e9;
  for (const auto& c : curve) best = std::min(best, (c - *p1).norm());
  EXPECT_LT(best, 0.5);
}

}  // namespace
}  // namespace p4
