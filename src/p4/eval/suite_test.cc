#include "p4/eval/suite.h"

#include <gtest/gtest.h>

#include "p4/core/error.h"
#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

TEST(Suite, ScenesAreDrawnFromTheirSeedWithinTheirFamily) {
  const SuiteScene a = DrawSuiteScene("webcam", "checking", 3);
  const SuiteScene b = DrawSuiteScene("webcam", "checking", 3);
  EXPECT_EQ(a.ToJson(), b.ToJson());
  EXPECT_EQ(a.seed, 1003u);
  EXPECT_EQ(a.width, 640);
  EXPECT_GE(a.exposure_ms, 8.0);
  EXPECT_LE(a.exposure_ms, 1000.0 / a.fps + 0.05);
  EXPECT_EQ(DrawSuiteScene("mono", "tuning", 2).cameras, 1);
  EXPECT_EQ(DrawSuiteScene("white", "tuning", 1).ball, "white");
  EXPECT_THROW(DrawSuiteScene("sports", "training", 1), Error);
  EXPECT_THROW(DrawSuiteScene("indoor", "tuning", 1), Error);
}

TEST(Suite, BallPixelsIsTheSmallestCamerasMedianDiameter) {
  Rig rig;
  rig.cameras = {testing::MakeCamera("near", {0.0, -3.0, 0.0}),
                 testing::MakeCamera("far", {0.0, -5.0, 0.0})};
  std::vector<TruthRow> truth(3);
  truth[0].in_play = truth[1].in_play = true;  // the ball at the origin, then 1 m nearer "far"
  truth[1].position = {0.0, -1.0, 0.0};
  truth[2].position = {0.0, -4.0, 0.0};  // out of play: not counted
  // "far": 8 px at 5 m and 10 px at 4 m, median of two -> the upper, 10 px; "near": 13.3, 20.
  EXPECT_NEAR(BallPixels(rig, truth), 1000.0 * 0.04 / 4.0, 1e-9);
  EXPECT_EQ(BallPixels(rig, {}), 0.0);
}

}  // namespace
}  // namespace p4
