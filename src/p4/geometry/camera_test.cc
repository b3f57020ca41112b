#include "p4/geometry/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

using testing::MakeCamera;

TEST(Camera, ProjectsThePrincipalAxisToThePrincipalPoint) {
  const Camera camera = MakeCamera("c", {0.0, -3.0, 1.0}, {0.0, 0.0, 1.0});
  const auto pixel = camera.Project({0.0, 0.0, 1.0});
  ASSERT_TRUE(pixel.has_value());
  EXPECT_NEAR(pixel->x(), camera.cx, 1e-9);
  EXPECT_NEAR(pixel->y(), camera.cy, 1e-9);
  EXPECT_NEAR((camera.Center() - Eigen::Vector3d(0.0, -3.0, 1.0)).norm(), 0.0, 1e-12);
  // A point above the target images above the principal point (image y points down).
  const auto above = camera.Project({0.0, 0.0, 1.3});
  ASSERT_TRUE(above.has_value());
  EXPECT_LT(above->y(), camera.cy - 50.0);
}

TEST(Camera, PointBehindTheCameraDoesNotProject) {
  const Camera camera = MakeCamera("c", {0.0, -3.0, 1.0}, {0.0, 0.0, 1.0});
  EXPECT_FALSE(camera.Project({0.0, -4.0, 1.0}).has_value());
  EXPECT_FALSE(camera.Sees({0.0, -4.0, 1.0}));
  EXPECT_TRUE(camera.Sees({0.0, 0.0, 1.0}));
  EXPECT_FALSE(camera.Sees({30.0, 0.0, 1.0}));  // in front, outside the image
}

TEST(Camera, DistortionRoundTrip) {
  Camera camera =
      MakeCamera("c", {0.0, -3.0, 1.0}, {0.0, 0.0, 1.0}, {-0.28, 0.09, 0.0012, -0.0008, -0.012});
  for (double x = -0.6; x <= 0.6; x += 0.1) {
    for (double y = -0.35; y <= 0.35; y += 0.07) {
      const Eigen::Vector2d n(x, y);
      const Eigen::Vector2d back = camera.Undistort(camera.Distort(n));
      EXPECT_NEAR((back - n).norm(), 0.0, 1e-10) << x << " " << y;
      const Eigen::Vector2d pixel = camera.PixelFromNormalized(n);
      EXPECT_NEAR((camera.NormalizedFromPixel(pixel) - n).norm(), 0.0, 1e-10);
    }
  }
}

TEST(Camera, RayThroughProjectionHitsThePoint) {
  const Camera camera = testing::ClubCameras()[1];  // with distortion
  const Eigen::Vector3d point(0.7, 0.3, 0.25);
  const auto pixel = camera.Project(point);
  ASSERT_TRUE(pixel.has_value());
  const Eigen::Vector3d dir = camera.RayDirection(*pixel);
  const Eigen::Vector3d to_point = point - camera.Center();
  EXPECT_NEAR((to_point - to_point.dot(dir) * dir).norm(), 0.0, 1e-9);
  EXPECT_NEAR(dir.norm(), 1.0, 1e-12);
}

TEST(Camera, InImageUsesPixelCentres) {
  const Camera camera = MakeCamera("c", {0.0, -3.0, 1.0});
  EXPECT_TRUE(camera.InImage({-0.5, -0.5}));
  EXPECT_FALSE(camera.InImage({-0.51, 10.0}));
  EXPECT_TRUE(camera.InImage({1279.4, 719.4}));
  EXPECT_FALSE(camera.InImage({1279.5, 100.0}));
  EXPECT_FALSE(camera.InImage({1270.0, 100.0}, 20.0));
}

TEST(ValidateCamera, RejectsEveryKindOfBadCamera) {
  const Camera good = MakeCamera("c", {0.0, -3.0, 1.0});
  std::string error;
  EXPECT_TRUE(ValidateCamera(good, &error)) << error;

  Camera zero_focal = good;
  zero_focal.fx = 0.0;
  EXPECT_FALSE(ValidateCamera(zero_focal, &error));
  EXPECT_NE(error.find("focal"), std::string::npos) << error;

  Camera no_size = good;
  no_size.height = 0;
  EXPECT_FALSE(ValidateCamera(no_size, &error));
  EXPECT_NE(error.find("image_height"), std::string::npos) << error;

  Camera nan_translation = good;
  nan_translation.cam_from_world.translation.x() = std::nan("");
  EXPECT_FALSE(ValidateCamera(nan_translation, &error));
  EXPECT_NE(error.find("translation"), std::string::npos) << error;

  Camera scaled = good;
  scaled.cam_from_world.rotation *= 1.01;
  EXPECT_FALSE(ValidateCamera(scaled, &error));
  EXPECT_NE(error.find("rotation"), std::string::npos) << error;

  Camera mirrored = good;
  mirrored.cam_from_world.rotation.row(0) *= -1.0;  // det = -1
  EXPECT_FALSE(ValidateCamera(mirrored, &error));
  EXPECT_NE(error.find("det"), std::string::npos) << error;

  Camera nan_distortion = good;
  nan_distortion.distortion[2] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ValidateCamera(nan_distortion, &error));
  EXPECT_NE(error.find("distortion"), std::string::npos) << error;
}

}  // namespace
}  // namespace p4
