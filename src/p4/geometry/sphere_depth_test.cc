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

TEST(SphereDepth, TheExpectedDiameterIsTheImagesToFirstOrder) {
  for (const Camera& camera : testing::ClubCameras()) {
    const Eigen::Vector3d centre(0.3, -0.2, 0.2);
    const auto [e1, e2] = SphereEdges(camera, centre, table::kBallRadius);
    // 2 r fx / depth against the exact edges: within 3 % over the table (off-axis stretching,
    // distortion), and nothing behind the camera.
    EXPECT_NEAR(SphereDiameterPx(camera, centre, table::kBallRadius) / (e1 - e2).norm(), 1.0, 0.03)
        << camera.name;
    const Eigen::Vector3d behind =
        camera.cam_from_world.Inverse() * Eigen::Vector3d(0.0, 0.0, -1.0);
    EXPECT_EQ(SphereDiameterPx(camera, behind, table::kBallRadius), 0.0);
  }
}

TEST(SphereDepth, RecoversTheCentreOnAndOffAxis) {
  for (const Camera& camera : testing::ClubCameras()) {
    for (const Eigen::Vector3d& centre :
         {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.3, 0.7, 0.4),
          Eigen::Vector3d(-1.3, -0.7, 0.05)}) {
      const auto [e1, e2] = SphereEdges(camera, centre, table::kBallRadius);
      const auto result = PointFromSphereImage(camera, 0.5 * (e1 + e2), (e1 - e2).norm(),
                                               EllipseAxis::kAlongRadius, table::kBallRadius);
      ASSERT_TRUE(result.has_value());
      // Exact but for the tangential part of camera end_a's distortion (edges off the radius).
      EXPECT_NEAR((result->point - centre).norm(), 0.0, 1e-5) << camera.name;
    }
  }
}

// The outline of the sphere's image (the tangent rays of its viewing cone), measured as a
// detector would: the centre of the extremes and the widths along and across the image radius.
struct Outline {
  Eigen::Vector2d centre;
  double along = 0.0, across = 0.0;
};
Outline SphereOutline(const Camera& camera, const Eigen::Vector3d& centre, double r) {
  const Eigen::Vector3d c = camera.cam_from_world * centre;
  const double alpha = std::asin(r / c.norm());
  const Eigen::Vector3d u = c.unitOrthogonal(), v = c.normalized().cross(u);
  Eigen::Vector2d radial = camera.Project(centre).value() - Eigen::Vector2d(camera.cx, camera.cy);
  radial.normalize();
  const Eigen::Vector2d tangential(-radial.y(), radial.x());
  double a0 = 1e9, a1 = -1e9, t0 = 1e9, t1 = -1e9;
  for (int k = 0; k < 7200; ++k) {
    const double phi = 2.0 * M_PI * k / 7200.0;
    const Eigen::Vector3d ray = std::cos(alpha) * c.normalized() +
                                std::sin(alpha) * (std::cos(phi) * u + std::sin(phi) * v);
    const Eigen::Vector2d px = camera.PixelFromNormalized(ray.head<2>() / ray.z());
    a0 = std::min(a0, px.dot(radial)), a1 = std::max(a1, px.dot(radial));
    t0 = std::min(t0, px.dot(tangential)), t1 = std::max(t1, px.dot(tangential));
  }
  return {0.5 * (a0 + a1) * radial + 0.5 * (t0 + t1) * tangential, a1 - a0, t1 - t0};
}

TEST(SphereDepth, EitherAxisOfTheEllipseGivesTheCentre) {
  Camera camera = testing::ClubCameras()[0];
  for (double& k : camera.distortion) k = 0.0;
  // Near the image's corner the two axes differ by 1/cos(theta): ~10 %.
  for (const Eigen::Vector3d& centre :
       {Eigen::Vector3d(0.0, 0.0, 0.2), Eigen::Vector3d(-1.6, 0.4, 0.1),
        Eigen::Vector3d(1.7, -0.5, 0.9)}) {
    const Outline o = SphereOutline(camera, centre, table::kBallRadius);
    ASSERT_TRUE(camera.InImage(o.centre));
    const auto along = PointFromSphereImage(camera, o.centre, o.along, EllipseAxis::kAlongRadius,
                                            table::kBallRadius);
    const auto across = PointFromSphereImage(camera, o.centre, o.across, EllipseAxis::kAcrossRadius,
                                             table::kBallRadius);
    ASSERT_TRUE(along && across);
    EXPECT_LT((along->point - centre).norm(), 0.001);
    EXPECT_LT((across->point - centre).norm(), 0.001);
  }
  // The minor axis taken for the major one: the ball lands 1/cos(theta) too far.
  const Eigen::Vector3d corner(-1.6, 0.4, 0.1);
  const Outline o = SphereOutline(camera, corner, table::kBallRadius);
  const auto wrong = PointFromSphereImage(camera, o.centre, o.across, EllipseAxis::kAlongRadius,
                                          table::kBallRadius);
  ASSERT_TRUE(wrong);
  const double true_distance = (camera.Center() - corner).norm();
  EXPECT_GT(wrong->distance - true_distance, 0.05 * true_distance);
}

TEST(SphereDepth, OnePixelOfDiameterErrorIsCentimetres) {
  // The paper's caveat: depth from the diameter is error-prone. At 4 m with f = 1000 px the ball
  // is ~10 px wide, so one pixel is ~10 % of the depth.
  const Camera camera = testing::ClubCameras()[0];
  const Eigen::Vector3d centre(0.0, 0.0, 0.2);
  const auto [e1, e2] = SphereEdges(camera, centre, table::kBallRadius);
  const double d = (e1 - e2).norm();
  const auto result = PointFromSphereImage(camera, 0.5 * (e1 + e2), d + 1.0,
                                           EllipseAxis::kAlongRadius, table::kBallRadius);
  ASSERT_TRUE(result.has_value());
  const double error = (result->point - centre).norm();
  EXPECT_GT(error, 0.1);
  EXPECT_LT(error, 0.6);
}

TEST(SphereDepth, RejectsDegenerateDiameters) {
  const Camera camera = testing::ClubCameras()[0];
  EXPECT_FALSE(
      PointFromSphereImage(camera, {600, 300}, 0.0, EllipseAxis::kAcrossRadius, 0.02).has_value());
  EXPECT_FALSE(
      PointFromSphereImage(camera, {600, 300}, -3.0, EllipseAxis::kAcrossRadius, 0.02).has_value());
  EXPECT_FALSE(
      PointFromSphereImage(camera, {600, 300}, std::nan(""), EllipseAxis::kAcrossRadius, 0.02)
          .has_value());
}

}  // namespace
}  // namespace p4
