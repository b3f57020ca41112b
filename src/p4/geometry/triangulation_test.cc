#include "p4/geometry/triangulation.h"

#include <gtest/gtest.h>

#include <random>

#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

std::vector<Observation> Observe(const std::vector<Camera>& cameras, const Eigen::Vector3d& point,
                                 int count) {
  std::vector<Observation> observations;
  for (int i = 0; i < count; ++i) {
    const auto pixel = cameras[i].Project(point);
    if (pixel) observations.push_back({i, *pixel});
  }
  return observations;
}

TEST(Triangulation, ExactFromTwoThreeAndFourCameras) {
  const auto cameras = testing::ClubCameras();
  const Eigen::Vector3d point(0.9, -0.2, 0.3);
  for (int count = 2; count <= 4; ++count) {
    const auto observations = Observe(cameras, point, count);
    ASSERT_EQ(static_cast<int>(observations.size()), count);
    const auto estimate = TriangulateObservations(cameras, observations);
    ASSERT_TRUE(estimate.has_value()) << count;
    EXPECT_NEAR((estimate->point - point).norm(), 0.0, 1e-8) << count;
    EXPECT_NEAR(estimate->mean_reprojection_px, 0.0, 1e-6);
    EXPECT_EQ(estimate->num_views, count);
    EXPECT_GT(estimate->conditioning, 0.01);
  }
}

TEST(Triangulation, NoiseOfHalfAPixelGivesMillimetres) {
  const auto cameras = testing::ClubCameras();
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.5);
  double sum_sq = 0.0;
  const int trials = 200;
  for (int k = 0; k < trials; ++k) {
    const Eigen::Vector3d point(-1.2 + 0.012 * k, 0.5 - 0.005 * k, 0.05 + 0.002 * k);
    auto observations = Observe(cameras, point, 3);
    for (auto& obs : observations) obs.pixel += Eigen::Vector2d(noise(rng), noise(rng));
    const auto estimate = TriangulateObservations(cameras, observations);
    ASSERT_TRUE(estimate.has_value());
    sum_sq += (estimate->point - point).squaredNorm();
    EXPECT_LT(estimate->mean_reprojection_px, 2.0);
  }
  const double rmse_mm = 1000.0 * std::sqrt(sum_sq / trials);
  EXPECT_LT(rmse_mm, 3.0);  // cameras 3.5-4.5 m away, f = 1000 px: ~2 mm per pixel
  EXPECT_GT(rmse_mm, 0.05);
}

TEST(Triangulation, OneCameraOnly) {
  const auto cameras = testing::ClubCameras();
  const auto observations = Observe(cameras, {0.0, 0.0, 0.2}, 1);
  EXPECT_FALSE(TriangulateObservations(cameras, observations).has_value());
  const std::vector<Ray> one{{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()}};
  EXPECT_FALSE(TriangulateRays(one).has_value());
}

TEST(Triangulation, ParallelRays) {
  const std::vector<Ray> parallel{{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                                  {{0.0, 0.1, 0.0}, {1.0, 0.0, 0.0}}};
  EXPECT_FALSE(TriangulateRays(parallel).has_value());
  // Nearly parallel (0.01 degree apart): rejected by the conditioning bound.
  const double a = 0.01 * M_PI / 180.0;
  const std::vector<Ray> nearly{{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                                {{0.0, 0.1, 0.0}, {std::cos(a), -std::sin(a), 0.0}}};
  EXPECT_FALSE(TriangulateRays(nearly).has_value());
  TriangulationOptions loose;
  loose.min_conditioning = 0.0;
  EXPECT_TRUE(TriangulateRays(nearly, loose).has_value());
}

TEST(Triangulation, PointBehindACamera) {
  // Two rays whose closest point lies behind the second ray's origin.
  const std::vector<Ray> rays{{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                              {{2.0, -1.0, 0.0}, Eigen::Vector3d(0.0, -1.0, 0.0)}};
  EXPECT_FALSE(TriangulateRays(rays).has_value());
  const std::vector<Ray> good{{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                              {{2.0, -1.0, 0.0}, Eigen::Vector3d(0.0, 1.0, 0.0)}};
  const auto result = TriangulateRays(good);
  ASSERT_TRUE(result.has_value());
  EXPECT_NEAR((result->point - Eigen::Vector3d(2.0, 0.0, 0.0)).norm(), 0.0, 1e-12);
}

TEST(Triangulation, SkewRaysGiveTheMidpointAndTheirDistance) {
  const std::vector<Ray> rays{{{-1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                              {{0.0, -1.0, 0.02}, Eigen::Vector3d(0.0, 1.0, 0.0)}};
  const auto result = TriangulateRays(rays);
  ASSERT_TRUE(result.has_value());
  EXPECT_NEAR((result->point - Eigen::Vector3d(0.0, 0.0, 0.01)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(result->rms_ray_distance, 0.01, 1e-12);
  TriangulationOptions bad;
  bad.min_conditioning = 2.0;
  std::string error;
  EXPECT_FALSE(bad.IsValid(&error));
}

// A camera 2 m from the ball and one 8 m away, both with the same pixel noise: one pixel is
// 2 mm at the near camera and 8 mm at the far one. The paper's plain least squares counts the
// rays' distances alike, so the far camera's noise pulls the point as much as the near one's;
// weighted by the views' sigmas the point follows each ray by its pixels (maximum likelihood
// for equal pixel noise): a lower reprojection cost in every trial and a smaller 3D error.
TEST(Triangulation, ViewsWeightedByTheirPixelsFollowTheCameraNearTheBall) {
  const Eigen::Vector3d target(0.3, 0.1, 0.4);
  const std::vector<Camera> cameras = {
      testing::MakeCamera("near", target + Eigen::Vector3d(0.0, -2.0, 0.3), target),
      testing::MakeCamera("far", target + Eigen::Vector3d(-5.6, 5.6, 1.0), target)};
  TriangulationOptions weighted;
  weighted.pixel_sigma = 0.5;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.5);
  // The direction across both rays, where each camera alone knows the point.
  const Eigen::Vector3d across = cameras[0]
                                     .RayDirection({cameras[0].cx, cameras[0].cy})
                                     .cross(cameras[1].RayDirection({cameras[1].cx, cameras[1].cy}))
                                     .normalized();
  double plain_sq = 0.0, weighted_sq = 0.0, plain_across = 0.0, weighted_across = 0.0;
  const int trials = 400;
  for (int k = 0; k < trials; ++k) {
    const Eigen::Vector3d point =
        target + Eigen::Vector3d(0.001 * (k % 20), 0.0, 0.002 * static_cast<double>(k / 20));
    auto observations = Observe(cameras, point, 2);
    ASSERT_EQ(observations.size(), 2u);
    for (auto& obs : observations) obs.pixel += Eigen::Vector2d(noise(rng), noise(rng));
    const auto plain = TriangulateObservations(cameras, observations);
    const auto ml = TriangulateObservations(cameras, observations, weighted);
    ASSERT_TRUE(plain && ml);
    const auto cost = [&](const Eigen::Vector3d& x) {
      double sum = 0.0;
      for (const auto& obs : observations)
        sum += (*cameras[obs.camera].Project(x) - obs.pixel).squaredNorm();
      return sum;
    };
    EXPECT_LE(cost(ml->point), cost(plain->point) + 1e-6) << k;
    plain_sq += (plain->point - point).squaredNorm();
    weighted_sq += (ml->point - point).squaredNorm();
    plain_across += std::pow((plain->point - point).dot(across), 2);
    weighted_across += std::pow((ml->point - point).dot(across), 2);
  }
  // Across both rays the near camera alone knows the point to 0.5 px = 1 mm, the far one to
  // 4 mm: weighted ~0.97 mm, the plain midpoint averages them, ~2.1 mm. Along each ray only the
  // other camera knows it, whatever the weights: the whole error is no worse.
  const double weighted_mm = 1000.0 * std::sqrt(weighted_across / trials);
  const double plain_mm = 1000.0 * std::sqrt(plain_across / trials);
  EXPECT_NEAR(weighted_mm, 0.97, 0.15);
  EXPECT_NEAR(plain_mm, 2.06, 0.3);
  EXPECT_LE(weighted_sq, plain_sq);
}

TEST(Triangulation, AViewOfItsOwnNoiseCountsTheLess) {
  // Three cameras; one view's centre is 3 px off (a half-hidden ball) and says so (sigma_px 3):
  // the point keeps to the other two.
  const auto cameras = testing::ClubCameras();
  const Eigen::Vector3d point(0.4, 0.2, 0.3);
  auto observations = Observe(cameras, point, 3);
  observations[1].pixel += Eigen::Vector2d(3.0, 0.0);
  TriangulationOptions weighted;
  weighted.pixel_sigma = 0.5;
  const auto blind = TriangulateObservations(cameras, observations, weighted);
  observations[1].sigma_px = 3.0;
  const auto told = TriangulateObservations(cameras, observations, weighted);
  ASSERT_TRUE(blind && told);
  const double blind_mm = 1000.0 * (blind->point - point).norm();
  const double told_mm = 1000.0 * (told->point - point).norm();
  EXPECT_GT(blind_mm, 2.0);  // 3 px at ~4 m: ~12 mm across its ray, shared with two exact views
  EXPECT_LT(told_mm, 0.25 * blind_mm);  // the noisy view weighs 1/37 of each other one
}

TEST(Triangulation, AWorldSigmaFloorEvensTheWeights) {
  // With a floor far above both cameras' pixel sigmas the weights are equal: the plain midpoint.
  const auto cameras = testing::ClubCameras();
  auto observations = Observe(cameras, {0.4, 0.2, 0.3}, 3);
  observations[0].pixel += Eigen::Vector2d(1.5, -1.0);
  TriangulationOptions floor;
  floor.pixel_sigma = 0.5;
  floor.ray_sigma_m = 10.0;
  const auto plain = TriangulateObservations(cameras, observations);
  const auto even = TriangulateObservations(cameras, observations, floor);
  ASSERT_TRUE(plain && even);
  EXPECT_LT((plain->point - even->point).norm(), 1e-7);
  TriangulationOptions bad;
  bad.ray_sigma_m = -1.0;
  std::string error;
  EXPECT_FALSE(bad.IsValid(&error));
}

}  // namespace
}  // namespace p4
