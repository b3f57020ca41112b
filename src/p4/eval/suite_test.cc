#include "p4/eval/suite.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

// Cameras out of step: the second camera started 0.05-4.9 s before the first, drifting, its
// stamps jittered; each scene has a twin (in step, or the same phones with a global shutter) and
// the simulate arguments say all of it.
TEST(Suite, OutOfStepScenesAndTheirTwins) {
  for (int k = 1; k <= 8; ++k) {
    const SuiteScene s = DrawSuiteScene("unsync", "tuning", k);
    ASSERT_EQ(s.cameras, 2);
    ASSERT_EQ(s.start_offsets_s.size(), 2u);
    EXPECT_EQ(s.start_offsets_s[0], 0.0);
    EXPECT_LE(s.start_offsets_s[1], -0.05 + 1e-9);
    EXPECT_GE(s.start_offsets_s[1], -4.9 - 1e-9);
    EXPECT_LE(std::abs(s.drift_ppm[1]), 50.0);
    EXPECT_EQ(s.camera_fps[0], 60);
    EXPECT_TRUE(s.camera_fps[1] == 60 || s.camera_fps[1] == 120);
    EXPECT_LE(s.stamp_jitter_ms, 0.5);
    EXPECT_EQ(s.twin, "in-step");
    const SuiteScene twin = s.Twin();
    EXPECT_TRUE(twin.start_offsets_s.empty());
    EXPECT_TRUE(twin.drift_ppm.empty());
    EXPECT_EQ(twin.stamp_jitter_ms, 0.0);
    EXPECT_EQ(twin.drop_rate, 0.0);
    EXPECT_EQ(twin.camera_fps, s.camera_fps);  // the same cameras
    EXPECT_TRUE(twin.twin.empty());
    const auto args = s.SimulateArgs();
    const auto at = std::find(args.begin(), args.end(), "--start-offsets");
    ASSERT_NE(at, args.end());
    EXPECT_EQ(*(at + 1), fmt::format("{:.5f},{:.5f}", 0.0, s.start_offsets_s[1]));
  }
  const SuiteScene phone = DrawSuiteScene("phone", "checking", 2);
  EXPECT_EQ(phone.width, 1920);
  ASSERT_EQ(phone.rolling_shutter_ms.size(), static_cast<std::size_t>(phone.cameras));
  for (const double readout : phone.rolling_shutter_ms) {
    EXPECT_GE(readout, phone.fps == 30 ? 15.0 : 10.0);
    EXPECT_LE(readout, phone.fps == 30 ? 25.0 : 16.0);
  }
  EXPECT_EQ(phone.twin, "global-shutter");
  const SuiteScene global = phone.Twin();
  EXPECT_TRUE(global.rolling_shutter_ms.empty());
  EXPECT_EQ(global.start_offsets_s, phone.start_offsets_s);  // still out of step
  EXPECT_THROW(DrawSuiteScene("sports", "tuning", 1).Twin(), Error);
  EXPECT_EQ(DrawSuiteScene("unsync-webcam", "tuning", 1).width, 640);
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
