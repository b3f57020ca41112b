#include "p4/track/fall_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "p4/sim/ball_physics.h"

namespace p4::track {
namespace {

// Samples of the simulator's flight (drag, Magnus, real bounce) at `rate` for `seconds`, with
// Gaussian noise of `sigma` (m) on each axis; the points carry that variance.
std::vector<FallPoint> SimFlight(const sim::BallState& start, double seconds, double rate,
                                 double sigma, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<FallPoint> out;
  sim::BallState s = start;
  const sim::BallParams params;
  const double step = 0.0005;
  double next = 0.0;
  for (double t = 0.0; t <= seconds + 1e-9; t += step) {
    if (t >= next - 1e-9) {
      const Eigen::Vector3d e(noise(*rng), noise(*rng), noise(*rng));
      out.push_back(
          {FromSeconds(next), s.position + e, sigma * sigma * Eigen::Matrix3d::Identity()});
      next += 1.0 / rate;
    }
    sim::WorldStep(&s, t, step, params);
  }
  return out;
}

// Something that moves level at `speed` along y at height z, seen at `rate` with noise.
std::vector<FallPoint> Level(double speed, double z, double rate, double sigma, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<FallPoint> out;
  for (int k = 0; k * (1.0 / rate) <= 0.2 + 1e-9; ++k) {
    const double t = k / rate;
    const Eigen::Vector3d p(-2.2 + noise(*rng), -0.3 + speed * t + noise(*rng), z + noise(*rng));
    out.push_back({FromSeconds(t), p, sigma * sigma * Eigen::Matrix3d::Identity()});
  }
  return out;
}

// A shoe or a shirt of the ball's colour moving level, at 2.5 m/s seen by 25 fps webcams and at
// 3 m/s seen at 60 fps (heights to 3 mm): the slow rule alone (under 2 m/s) lets it go on; what
// the air can give a ball that fast (150 rev/s of backspin at most) is 3.3-4.6 m/s^2 short of
// gravity, and over 0.2 s the fall is known to 0.6 m/s^2: it is told. (At 25 fps and 3.5 m/s
// the bound is 2 m/s^2 short of gravity, within 3 sigmas: nothing is told.)
TEST(FallCheck, SomethingMovingLevelAtTwoAndAHalfMetresASecondDoesNotFallAsABall) {
  std::mt19937 rng(7);
  const FlightModel model;
  for (const auto& [rate, speed] : {std::pair{25.0, 2.5}, std::pair{60.0, 3.0}}) {
    for (double z : {-0.72, 0.3}) {
      for (int trial = 0; trial < 10; ++trial) {
        const auto points = Level(speed, z, rate, 0.003, &rng);
        const FallFit fit = JudgeFall(points, {}, model);
        ASSERT_TRUE(fit.judged) << speed << " m/s at z " << z;
        EXPECT_TRUE(fit.not_falling)
            << speed << " m/s at " << rate << " fps, z " << z << ": fall " << fit.fall << " +- "
            << fit.fall_sigma << ", least " << fit.least_fall;
      }
    }
  }
}

// The simulator's ball with the most backspin it is given (150 rev/s, lifting it) at 1.5-8 m/s,
// at 25 and 60 fps: noise-free, it falls at least as fast as the bound says (the bound holds
// for the simulator's physics, which the tracker does not share); with 4 mm of noise no window
// is taken for something that does not fall.
TEST(FallCheck, ABallWithTheMostBackspinFallsAsTheBoundSays) {
  const FlightModel model;
  std::mt19937 rng(11);
  int judged = 0;
  for (double speed : {1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0}) {
    for (double rise : {-1.0, 0.0, 1.0}) {
      sim::BallState start;
      start.position = {-2.6, 0.1, 0.6};
      start.velocity = {speed, 0.0, rise};
      start.spin = {0.0, -2.0 * M_PI * 150.0, 0.0};  // backspin: the Magnus force lifts it
      std::mt19937 none(1);
      const auto exact = SimFlight(start, 0.2, 60.0, 0.0, &none);
      const FallFit fit = JudgeFall(exact, {}, model);
      ASSERT_TRUE(fit.judged) << speed << " m/s, rising " << rise;
      EXPECT_GE(fit.fall, fit.least_fall) << speed << " m/s, rising " << rise;
      for (double rate : {25.0, 60.0}) {
        for (int trial = 0; trial < 5; ++trial) {
          const auto points = SimFlight(start, 0.2, rate, 0.004, &rng);
          const FallFit noisy = JudgeFall(points, {}, model);
          judged += noisy.judged ? 1 : 0;
          EXPECT_FALSE(noisy.not_falling) << speed << " m/s at " << rate << " fps: fall "
                                          << noisy.fall << " +- " << noisy.fall_sigma;
        }
      }
    }
  }
  EXPECT_GT(judged, 150);  // of 210: the windows were judged, not passed over
}

// A window across a bounce (two parabolas), one on the table (a rolling ball), one too short or
// of too few points: not judged.
TEST(FallCheck, AWindowItCannotJudgeIsNotJudged) {
  const FlightModel model;
  std::mt19937 rng(3);
  sim::BallState start;
  start.position = {0.3, 0.1, 0.25};
  start.velocity = {3.0, 0.0, -1.0};  // bounces at about 0.12 s
  EXPECT_FALSE(JudgeFall(SimFlight(start, 0.2, 60.0, 0.001, &rng), {}, model).judged);
  // A slow ball lifted by a racket between two samples (the heights accelerate upward).
  std::vector<FallPoint> lifted;
  for (int k = 0; k <= 5; ++k) {
    const double s = k / 25.0, hit = 0.1;
    const double z =
        s < hit ? 0.3 - 1.0 * s - 4.9 * s * s : 0.3 - 1.0 * hit - 4.9 * hit * hit + 2.0 * (s - hit);
    lifted.push_back(
        {FromSeconds(s), {-1.9 + 2.0 * s, 0.1, z}, 1e-6 * Eigen::Matrix3d::Identity()});
  }
  EXPECT_FALSE(JudgeFall(lifted, {}, model).judged);
  std::vector<FallPoint> rolling;
  for (int k = 0; k <= 12; ++k)
    rolling.push_back(
        {FromSeconds(k / 60.0), {0.5, 0.1, 0.02}, 1e-6 * Eigen::Matrix3d::Identity()});
  EXPECT_FALSE(JudgeFall(rolling, {}, model).judged);
  const auto level = Level(3.0, 0.3, 25.0, 0.001, &rng);
  EXPECT_FALSE(JudgeFall(std::span(level).first(4), {}, model).judged);  // 0.12 s, 4 points
  FallCheckOptions off;
  off.window_s = 0.0;
  EXPECT_FALSE(JudgeFall(level, off, model).judged);
}

TEST(FallCheck, ValidatesItsOptions) {
  std::string error;
  EXPECT_TRUE(FallCheckOptions{}.IsValid(&error));
  FallCheckOptions bad;
  bad.max_spin = -1.0;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_NE(error.find("max_spin"), std::string::npos) << error;
  bad = {};
  bad.fit_rms = 0.0;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_NE(error.find("fit_rms"), std::string::npos) << error;
}

}  // namespace
}  // namespace p4::track
