#include "p4/track/kalman_filter.h"

#include <gtest/gtest.h>

namespace p4::track {
namespace {

TEST(KalmanFilter, PaperMatricesAndStart) {
  KalmanOptions options;
  options.noise = KalmanOptions::Noise::kPaper;
  KalmanFilter filter(options);
  Vector6d start;
  start << 0, 0, 0, 1, 1, 1;
  EXPECT_EQ(filter.state(), start);
  EXPECT_EQ(filter.covariance(), Matrix6d::Identity());
  const Matrix6d a = KalmanFilter::TransitionMatrix(0.01);
  EXPECT_DOUBLE_EQ(a(0, 3), 0.01);
  EXPECT_DOUBLE_EQ(a(2, 5), 0.01);
  EXPECT_DOUBLE_EQ(a(3, 0), 0.0);
  const Vector6d bu = filter.ControlTerm(0.01);
  EXPECT_DOUBLE_EQ(bu(2), -0.5 * 9.81 * 1e-4);
  EXPECT_DOUBLE_EQ(bu(5), -9.81 * 0.01);
  EXPECT_DOUBLE_EQ(bu(1), 0.0);
  EXPECT_EQ(filter.ProcessNoise(0.01), 1e-5 * Matrix6d::Identity());
  // The paper's R (4 cm) is used whatever covariance the measurement brings.
  filter.Predict(0.01);
  const double d_small = filter.Mahalanobis2({0.1, 0.0, 0.0}, 1e-9 * Eigen::Matrix3d::Identity());
  const double d_large = filter.Mahalanobis2({0.1, 0.0, 0.0}, 1.0 * Eigen::Matrix3d::Identity());
  EXPECT_DOUBLE_EQ(d_small, d_large);
}

TEST(KalmanFilter, LearnsVelocityOnAParabola) {
  KalmanFilter filter;
  Vector6d truth;
  truth << -1.2, 0.3, 0.25, 8.0, -1.0, 2.0;
  const double dt = 1.0 / 120.0;
  Vector6d start = truth;
  start.tail<3>().setZero();
  Matrix6d p = Matrix6d::Identity() * 1e-6;
  p.bottomRightCorner<3, 3>() *= 1e8;
  filter.Reset(start, p);
  for (int k = 0; k < 30; ++k) {
    truth = KalmanFilter::TransitionMatrix(dt) * truth + filter.ControlTerm(dt);
    filter.Predict(dt);
    filter.Update(truth.head<3>(), 1e-6 * Eigen::Matrix3d::Identity());
  }
  EXPECT_LT((filter.state().tail<3>() - truth.tail<3>()).norm(), 0.05);
  EXPECT_LT((filter.state().head<3>() - truth.head<3>()).norm(), 0.002);
}

TEST(KalmanFilter, AccelerationNoiseGrowsWithTheStep) {
  KalmanFilter filter;
  EXPECT_GT(filter.ProcessNoise(0.02)(0, 0), 7.0 * filter.ProcessNoise(0.01)(0, 0));
  KalmanOptions bad;
  bad.accel_sigma = 0.0;
  std::string error;
  EXPECT_FALSE(bad.IsValid(&error));
}

}  // namespace
}  // namespace p4::track
