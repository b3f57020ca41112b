#include "p4/eval/evaluate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

// 10 truth rows at 100 Hz: the ball in play for rows 2..9, seen by every camera.
std::vector<TruthRow> Truth() {
  std::vector<TruthRow> truth;
  truth.reserve(10);
  for (int i = 0; i < 10; ++i)
    truth.push_back({0.01 * i, Eigen::Vector3d(0.1 * i, 0, 0.3), i >= 2});
  return truth;
}

Rig TwoCameras() {
  Rig rig;
  const auto cameras = testing::ClubCameras();
  rig.cameras = {cameras[0], cameras[1]};
  return rig;
}

TrajectoryRow Row(const TruthRow& truth, double error_m, bool measured) {
  TrajectoryRow row;
  row.t = truth.t;  // rows between the truth's: ARowBetweenTheTruthsRowsMeetsTheTruthAtItsOwnTime
  row.position = truth.position + Eigen::Vector3d(0, 0, error_m);
  row.measured = measured;
  row.cameras = measured ? 2 : 0;
  return row;
}

TEST(Evaluate, CountsEveryMeasuredRowInPlayInTheErrorAndFarOnesAsFalse) {
  const auto truth = Truth();
  std::vector<TrajectoryRow> run;
  run.push_back(Row(truth[1], 0.0, true));     // no ball in play: false positive
  run.push_back(Row(truth[2], 0.003, true));   // 3 mm
  run.push_back(Row(truth[3], 0.004, true));   // 4 mm
  run.push_back(Row(truth[4], 0.120, true));   // 120 mm: false, but counted in the error
  run.push_back(Row(truth[5], 0.010, false));  // filled, not measured: only in rmse_all
  const EvalReport r = Evaluate(truth, run, TwoCameras(), {});
  EXPECT_EQ(r.frames, 10);
  EXPECT_EQ(r.frames_in_play, 8);
  EXPECT_EQ(r.measured_rows, 4);
  EXPECT_NEAR(r.position_rmse_mm, std::sqrt((9.0 + 16.0 + 14400.0) / 3.0), 1e-6);
  EXPECT_NEAR(r.position_rmse_all_mm, std::sqrt((9.0 + 16.0 + 14400.0 + 100.0) / 4.0), 1e-6);
  EXPECT_NEAR(r.false_positive_rate, 2.0 / 4.0, 1e-12);
  // Recall: rows 2 and 3 of the 8 in play (all seen by both cameras) have a true measurement.
  EXPECT_EQ(r.frames_seen, 8);
  EXPECT_NEAR(r.recall, 2.0 / 8.0, 1e-12);
}

TEST(Evaluate, RecallCountsOnlyFramesSeenByEnoughCameras) {
  const auto truth = Truth();
  std::vector<std::vector<float>> visibility(truth.size(), {1.0F, 1.0F});
  visibility[2] = {1.0F, 0.0F};  // one camera only: not a frame the rig must measure
  std::vector<TrajectoryRow> run{Row(truth[2], 0.001, true), Row(truth[3], 0.001, true)};
  const EvalReport r = Evaluate(truth, run, TwoCameras(), visibility);
  EXPECT_EQ(r.frames_seen, 7);
  EXPECT_NEAR(r.recall, 1.0 / 7.0, 1e-12);
}

TEST(Evaluate, ARowBetweenTheTruthsRowsMeetsTheTruthAtItsOwnTime) {
  // The truth at 100 Hz, a ball flying at 10 m/s under gravity; a row 4 ms after a truth row (a
  // camera out of step) is compared with where the ball was then, not 40 mm back.
  std::vector<TruthRow> truth;
  const auto at = [](double t) -> Eigen::Vector3d {
    return {10.0 * t, 0.0, 0.5 + 2.0 * t - 0.5 * 9.81 * t * t};
  };
  for (int i = 0; i < 10; ++i) {
    const double t = 0.01 * i;
    truth.push_back({t, at(t), true, Eigen::Vector3d(10.0, 0.0, 2.0 - 9.81 * t)});
  }
  std::vector<TrajectoryRow> run(1);
  run[0].t = 0.054;
  run[0].position = at(0.054);
  run[0].measured = true;
  const EvalReport r = Evaluate(truth, run, {}, {}, {});
  EXPECT_LT(r.position_rmse_mm, 0.01);
  EXPECT_EQ(r.false_positive_rate, 0.0);
}

TEST(Evaluate, ARowJustAfterAHitMeetsTheTruthOnItsSideOfTheHit) {
  // The truth at 60 Hz; the ball flies at -5 m/s in x until a hit at t = 0.036 s at x = 0, then
  // at +10 m/s. A row at 0.038 s (out of step) is nearest the truth row at 0.0333 s, before the
  // hit, but is compared with the flight after it (+20 mm), not the one before carried across
  // the hit (-10 mm).
  const double hit = 0.036;
  const auto at = [&](double t) -> Eigen::Vector3d {
    return {t < hit ? -5.0 * (t - hit) : 10.0 * (t - hit), 0.0, 0.5};
  };
  const auto velocity = [&](double t) -> Eigen::Vector3d {
    return {t < hit ? -5.0 : 10.0, 0.0, 0.0};
  };
  std::vector<TruthRow> truth;
  for (int i = 0; i < 6; ++i) {
    const double t = i / 60.0;
    truth.push_back({t, at(t), true, velocity(t)});
  }
  const auto row_at = [&](double t) {
    std::vector<TrajectoryRow> run(1);
    run[0].t = t;
    run[0].position = at(t);
    run[0].measured = true;
    return run;
  };
  EvalOptions options;
  options.gravity = 0.0;                          // the flight above is straight
  for (const double t : {0.035, 0.038, 0.045}) {  // before the hit, across it, after it
    EXPECT_LT(Evaluate(truth, row_at(t), {}, {}, options).position_rmse_mm, 0.01) << t;
  }
  // With contacts taken for drag (a bound above the jump), the nearest row is carried across.
  options.contact_mps = 100.0;
  EXPECT_NEAR(Evaluate(truth, row_at(0.038), {}, {}, options).position_rmse_mm, 30.0, 0.1);
}

TEST(Evaluate, EmptyInputsGiveZeros) {
  const EvalReport r = Evaluate({}, {}, TwoCameras(), {});
  EXPECT_EQ(r.frames, 0);
  EXPECT_EQ(r.position_rmse_mm, 0.0);
  EXPECT_EQ(r.recall, 0.0);
}

}  // namespace
}  // namespace p4
