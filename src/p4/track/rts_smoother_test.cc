// The smoother on flights drawn from the filter's own model (gravity, white-noise acceleration,
// no drag: linear), where its answers are known: the smoothed errors have the smoothed
// covariance (NEES of 3 for a position), they are smaller than the filter's, and a track's
// start cuts it off from the steps before.
#include "p4/track/rts_smoother.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

namespace p4::track {
namespace {

constexpr double kRate = 25.0;
constexpr int kSteps = 25;
constexpr double kPixelLikeSigma = 0.005;  // m, each axis of a position measurement

KalmanOptions LinearModel() {
  KalmanOptions o;
  o.drag_per_mass = 0.0;
  o.accel_sigma = 8.0;
  return o;
}

struct DrawnRun {
  std::vector<Vector6d> truth;
  std::vector<FilterStep> steps;
};

// A flight from the model with its process noise, measured at every step but those in
// [gap_begin, gap_end), filtered as the ball tracker does (ball_tracker.cc).
DrawnRun DrawRun(std::mt19937* rng, int gap_begin, int gap_end) {
  const KalmanOptions options = LinearModel();
  KalmanFilter model(options);
  const double dt = 1.0 / kRate;
  const Eigen::LLT<Matrix6d> q(model.ProcessNoise(dt));
  std::normal_distribution<double> normal;
  const auto draw6 = [&] {
    Vector6d w;
    for (int i = 0; i < 6; ++i) w(i) = normal(*rng);
    return w;
  };
  DrawnRun run;
  Vector6d x;
  x << -1.2, 0.2, 0.3, 6.0, -0.5, 2.0;
  for (int k = 0; k < kSteps; ++k) {
    if (k > 0) {
      x = KalmanFilter::TransitionMatrix(dt) * x + model.ControlTerm(dt) +
          Vector6d(q.matrixL() * draw6());
    }
    run.truth.push_back(x);
  }
  const Eigen::Matrix3d r = kPixelLikeSigma * kPixelLikeSigma * Eigen::Matrix3d::Identity();
  const auto measure = [&](int k) {
    return Eigen::Vector3d(run.truth[k].head<3>() + kPixelLikeSigma * draw6().head<3>());
  };
  KalmanFilter filter(options);
  Matrix6d p0 = Matrix6d::Zero();
  p0.topLeftCorner<3, 3>() = r;
  p0.bottomRightCorner<3, 3>() = 4.0 * Eigen::Matrix3d::Identity();  // 2 m/s
  Vector6d x0;
  x0 << measure(0), run.truth[0].tail<3>() + 2.0 * draw6().tail<3>();
  filter.Reset(x0, p0);
  FilterStep start;
  start.t = 0;
  start.prior_state = start.state = filter.state();
  start.prior_covariance = start.covariance = filter.covariance();
  start.start = true;
  run.steps.push_back(start);
  for (int k = 1; k < kSteps; ++k) {
    FilterStep s;
    s.t = FromSeconds(k * dt);
    filter.ResetTransition();
    filter.Predict(dt);
    s.prior_state = filter.state();
    s.prior_covariance = filter.covariance();
    s.transition = filter.transition();
    if (k < gap_begin || k >= gap_end) filter.Update(measure(k), r);
    s.state = filter.state();
    s.covariance = filter.covariance();
    run.steps.push_back(s);
  }
  return run;
}

double PositionNees(const Vector6d& estimate, const Matrix6d& covariance, const Vector6d& truth) {
  const Eigen::Vector3d e = estimate.head<3>() - truth.head<3>();
  return e.dot(covariance.topLeftCorner<3, 3>().ldlt().solve(e));
}

TEST(RtsSmoother, SmoothedErrorsMatchTheirCovarianceAndBeatTheFilters) {
  std::mt19937 rng(7);
  constexpr int kRuns = 400;
  constexpr int kProbe = 12;  // inside a gap of 3 steps without measurements (11-13)
  double nees_smoothed = 0.0, nees_filtered = 0.0, se_smoothed = 0.0, se_filtered = 0.0;
  double var_smoothed = 0.0, var_filtered = 0.0;
  for (int run = 0; run < kRuns; ++run) {
    const DrawnRun r = DrawRun(&rng, 11, 14);
    const std::vector<SmoothedState> s = SmoothSteps(r.steps);
    ASSERT_EQ(s.size(), r.steps.size());
    // The newest step is as filtered.
    EXPECT_EQ(s.back().state, r.steps.back().state);
    EXPECT_EQ(s.back().covariance, r.steps.back().covariance);
    const Vector6d& truth = r.truth[kProbe];
    nees_smoothed += PositionNees(s[kProbe].state, s[kProbe].covariance, truth);
    nees_filtered += PositionNees(r.steps[kProbe].state, r.steps[kProbe].covariance, truth);
    se_smoothed += (s[kProbe].state - truth).head<3>().squaredNorm();
    se_filtered += (r.steps[kProbe].state - truth).head<3>().squaredNorm();
    var_smoothed += s[kProbe].covariance.topLeftCorner<3, 3>().trace();
    var_filtered += r.steps[kProbe].covariance.topLeftCorner<3, 3>().trace();
  }
  // A consistent estimate: the mean NEES of a 3D position is 3 (sd of the mean over 400 runs
  // is 0.12); the filter's own covariance is consistent too.
  EXPECT_NEAR(nees_smoothed / kRuns, 3.0, 0.4);
  EXPECT_NEAR(nees_filtered / kRuns, 3.0, 0.4);
  // In the middle of the gap the measurements after it pin the ball down: the smoothed
  // variance is a small part of the filter's, and so are the errors.
  EXPECT_LT(var_smoothed, 0.25 * var_filtered);
  EXPECT_LT(se_smoothed, 0.35 * se_filtered);
  std::printf("gap middle: rms error %.1f mm smoothed, %.1f mm filtered\n",
              1000.0 * std::sqrt(se_smoothed / kRuns), 1000.0 * std::sqrt(se_filtered / kRuns));
}

TEST(RtsSmoother, AStartCutsATrackOffFromTheStepsBefore) {
  std::mt19937 rng(3);
  const DrawnRun a = DrawRun(&rng, kSteps, kSteps);
  const DrawnRun b = DrawRun(&rng, kSteps, kSteps);
  std::vector<FilterStep> joined(a.steps.begin(), a.steps.begin() + 10);
  for (const FilterStep& s : b.steps) {
    joined.push_back(s);
    joined.back().t += FromSeconds(10 / kRate);
  }
  const std::vector<SmoothedState> together = SmoothSteps(joined);
  const std::vector<SmoothedState> first =
      SmoothSteps(std::span<const FilterStep>(a.steps.data(), 10));
  const std::vector<SmoothedState> second = SmoothSteps(b.steps);
  ASSERT_EQ(together.size(), 10u + b.steps.size());
  for (int k = 0; k < 10; ++k) EXPECT_EQ(together[k].state, first[k].state) << k;
  for (std::size_t k = 0; k < b.steps.size(); ++k) {
    EXPECT_EQ(together[10 + k].state, second[k].state) << k;
  }
  // And smoothing changed the steps before each track's newest one.
  EXPECT_GT((first[5].state - a.steps[5].state).norm(), 1e-6);
}

}  // namespace
}  // namespace p4::track
