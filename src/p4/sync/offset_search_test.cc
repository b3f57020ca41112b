#include "p4/sync/offset_search.h"

#include <gtest/gtest.h>

#include "p4/sync/sync_test_world.h"

namespace p4::sync {
namespace {

using testing::Recording;

struct Found {
  OffsetResult result;
  double truth_offset = 0.0;
};

// Records a rally with camera "side" as the rig's clock and "end" at `b`, and searches.
OffsetResult Search(const Recording& b, double reference_fps = 60.0, double seconds = 12.0,
                    OffsetOptions options = {}, uint64_t rally_seed = 11,
                    uint64_t record_seed = 1) {
  const testing::Rally rally(seconds + 6.0, rally_seed);
  Recording a;
  a.fps = reference_fps;
  a.seconds = seconds;
  a.lean_px = b.lean_px;
  const Camera ref = testing::SideCamera(), cam = testing::EndCamera();
  const auto ref_tracks = LinkTracks(testing::Record(ref, rally, a, record_seed));
  const auto b_tracks = LinkTracks(testing::Record(cam, rally, b, record_seed + 1));
  return FindOffset(ref, ref_tracks, cam, b_tracks, options);
}

TEST(FindOffset, RecoversWholeFrameAndSubFrameShifts) {
  // Offsets of whole frames and fractions, either sign, up to the search's reach.
  for (const double offset : {0.0, 4.0, -2.5, 0.1234, -0.00761, 1.01234}) {
    Recording b;
    b.offset_s = offset;
    b.seconds = 12.0 - std::max(0.0, offset);
    const OffsetResult r = Search(b);
    ASSERT_TRUE(r.found) << offset << ": " << r.why;
    EXPECT_NEAR(r.offset_s, offset, 0.5e-3) << "offset " << offset;
    EXPECT_LT(r.sigma_s, 0.5e-3);
    EXPECT_GT(r.sigma_s, 0.0);
    EXPECT_LT(r.rms_px, 1.0);
    EXPECT_FALSE(r.rate_fitted);
    // Cameras in step are found in step (0 exactly), a third of a frame off is not.
    EXPECT_EQ(r.in_step, offset == 0.0) << offset;
  }
}

TEST(FindOffset, ViewsThatLeanAlikeAlongEachFlightWidenTheSigma) {
  // Cameras in step whose views of each flight lean by their own 1.5 px (the lit half, the
  // background): the offset found is off by the leans' mean over a few flights, not by the
  // noise of hundreds of independent points. Its sigma must say so: 0 lies within the in-step
  // bound in most rallies (with the points' sigma alone, 0.08-0.12 ms, 4 of these 10 were
  // found 0.33-0.45 ms off, 3.5-4.8 sigmas).
  int in_step = 0, within_3_sigma = 0;
  const int rallies = 10;
  for (uint64_t seed = 1; seed <= rallies; ++seed) {
    Recording b;
    b.lean_px = 1.5;
    const OffsetResult r = Search(b, 60.0, 12.0, {}, seed, 10 * seed);
    ASSERT_TRUE(r.found) << seed << ": " << r.why;
    in_step += r.in_step;
    if (r.in_step || std::abs(r.offset_s) <= 3.0 * r.sigma_s) ++within_3_sigma;
    EXPECT_LT(std::abs(r.offset_s), 1.5e-3) << seed;  // still found to a tenth of a frame
  }
  EXPECT_GE(in_step, 8);
  EXPECT_GE(within_3_sigma, 9);
}

TEST(FindOffset, CamerasAtDifferentRatesAndDroppedFrames) {
  Recording b;
  b.fps = 120.0;
  b.offset_s = 0.3333;
  b.drop_rate = 0.1;
  const OffsetResult r = Search(b, 60.0);
  ASSERT_TRUE(r.found) << r.why;
  EXPECT_NEAR(r.offset_s, 0.3333, 0.5e-3);
  // 25 and 30 fps webcams, one of them dark for a second.
  Recording slow;
  slow.fps = 25.0;
  slow.offset_s = -1.2;
  slow.dark_from_s = 4.0, slow.dark_to_s = 5.0;
  const OffsetResult s = Search(slow, 30.0);
  ASSERT_TRUE(s.found) << s.why;
  EXPECT_NEAR(s.offset_s, -1.2, 0.5e-3);
}

TEST(FindOffset, FitsTheDriftOverALongRecording) {
  Recording b;
  b.offset_s = 0.2;
  b.drift_ppm = 60.0;  // 2.4 ms over the 40 s
  b.seconds = 40.0;
  const OffsetResult r = Search(b, 60.0, 40.0);
  ASSERT_TRUE(r.found) << r.why;
  EXPECT_TRUE(r.rate_fitted);
  EXPECT_NEAR(r.offset_s, 0.2, 0.5e-3);
  EXPECT_NEAR((r.rate - 1.0) * 1e6, 60.0, 10.0);
  // At the end of the recording the clock still agrees within half a millisecond.
  EXPECT_NEAR(r.offset_s + r.rate * 40.0, 0.2 + (1.0 + 60e-6) * 40.0, 0.5e-3);
}

// Both cameras read their 720 rows out over 20 ms (27.8 us a row; phones). The rows' delays
// are found with the offset: the offset within half a millisecond, each line time within 10 %,
// and the epipolar distances back to the noise's (measured: 0.09 ms off, 27.4 and 27.6 us,
// 0.48 px); without, the rows' delays are left in them (3.7 ms off, 1.12 px).
TEST(FindOffset, FitsRollingShutterLineTimes) {
  const double line_time = 0.012 / 720.0;  // a 12 ms readout (the frame: 16.7 ms)
  const testing::Rally rally(18.0, 11);
  Recording a, b;
  a.line_time_s = b.line_time_s = line_time;
  b.offset_s = -1.4321;
  b.seconds = 10.0;
  a.seconds = 10.0;
  const Camera ref = testing::SideCamera(), cam = testing::EndCamera();
  const auto ref_tracks = LinkTracks(testing::Record(ref, rally, a, 1));
  const auto b_tracks = LinkTracks(testing::Record(cam, rally, b, 2));
  OffsetOptions options;
  options.fit_line_times = true;
  const OffsetResult r = FindOffset(ref, ref_tracks, cam, b_tracks, options);
  ASSERT_TRUE(r.found) << r.why;
  EXPECT_TRUE(r.line_times_fitted);
  EXPECT_FALSE(r.in_step);
  EXPECT_NEAR(r.offset_s, b.offset_s, 0.5e-3);
  EXPECT_NEAR(r.line_time_s, line_time, 0.1 * line_time);
  EXPECT_NEAR(r.reference_line_time_s, line_time, 0.1 * line_time);
  EXPECT_LT(r.rms_px, 0.8);
  const OffsetResult global = FindOffset(ref, ref_tracks, cam, b_tracks);
  ASSERT_TRUE(global.found) << global.why;
  EXPECT_FALSE(global.line_times_fitted);
  EXPECT_GT(global.rms_px, 1.5 * r.rms_px);
}

TEST(FindOffset, RefusesWithTooLittleMotion) {
  // Half a second of recording: one flight at most.
  Recording b;
  b.offset_s = 0.05;
  b.seconds = 0.5;
  const OffsetResult r = Search(b, 60.0, 0.5);
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.why.find("too little ball motion"), std::string::npos) << r.why;
  // Nothing at all.
  const OffsetResult none = FindOffset(testing::SideCamera(), {}, testing::EndCamera(), {});
  EXPECT_FALSE(none.found);
  EXPECT_NE(none.why.find("not seen"), std::string::npos) << none.why;
}

}  // namespace
}  // namespace p4::sync
