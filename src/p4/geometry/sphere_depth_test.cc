#include "p4/geometry/sphere_depth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "p4/core/table.h"
#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

// The two edge pixels of the sphere's image along the image radius: the tangent rays of the
// viewing cone in the plane of the optical axis and the centre direction.
std::pair<Eigen::Vector2d, Eigen::Vector2d> SphereEdges(const Camera& camera,
                                                        const Eigen::Vector3d& centre, double r) {
  const Eigen::Vector3d c = camera.cam_from_world * centre;
  const double alpha = std::asin(r / c.norm());
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(c);
  axis = axis.norm() > 1e-12 ? Eigen::Vector3d(axis.normalized()) : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = Eigen::AngleAxisd(alpha, axis) * c;
  const Eigen::Vector3d e2 = Eigen::AngleAxisd(-alpha, axis) * c;
  return {camera.PixelFromNormalized(e1.head<2>() / e1.z()),
          camera.PixelFromNormalized(e2.head<2>() / e2.z())};
}

TEST(SphereDepth, RecoversTheCentreOnAndOffAxis) {
  for (const Camera& camera : testing::ClubCameras()) {
    for (const Eigen::Vector3d& centre :
         {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.3, 0.7, 0.4),
          Eigen::Vector3d(-1.3, -0.7, 0.05)}) {
      const auto [e1, e2] = SphereEdges(camera, centre, table::kBallRadius);
      const auto result =
          PointFromSphereImage(camera, 0.5 * (e1 + e2), (e1 - e2).norm(), table::kBallRadius);
      ASSERT_TRUE(result.has_value());
      // Exact but for the tangential part of camera end_a's distortion (edges off the radius).
      EXPECT_NEAR((result->point - centre).norm(), 0.0, 1e-5) << camera.name;
    }
  }
}

TEST(SphereDepth, OnePixelOfDiameterErrorIsCentimetres) {
  // The paper's caveat: depth from the diameter is error-prone. At 4 m with f = 1000 px the ball
  // is ~10 px wide, so one pixel is ~10 % of the depth.
  const Camera camera = testing::ClubCameras()[0];
  const Eigen::Vector3d centre(0.0, 0.0, 0.2);
  const auto [e1, e2] = SphereEdges(camera, centre, table::kBallRadius);
  const double d = (e1 - e2).norm();
  const auto result = PointFromSphereImage(camera, 0.5 * (e1 + e2), d + 1.0, table::kBallRadius);
  ASSERT_TRUE(result.has_value());
  const double error = (result->point - centre).norm();
  EXPECT_GT(error, 0.1);
  EXPECT_LT(error, 0.6);
}

TEST(SphereDepth, RejectsDegenerateDiameters) {
  const Camera camera = testing::ClubCameras()[0];
  EXPECT_FALSE(PointFromSphereImage(camera, {600, 300}, 0.0, 0.02).has_value());
  EXPECT_FALSE(PointFromSphereImage(camera, {600, 300}, -3.0, 0.02).has_value());
  EXPECT_FALSE(PointFromSphereImage(camera, {600, 300}, std::nan(""), 0.02).has_value());
}

}  // namespace
}  // namespace p4
