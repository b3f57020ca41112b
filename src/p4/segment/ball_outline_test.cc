// The centre of a ball of known size from its outline (ball_outline.h) on painted frames with
// known centres.
#include "p4/segment/ball_outline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "p4/segment/ball_edge.h"
#include "p4/segment/test_images.h"

namespace p4::segment {
namespace {

using testing::Disc;
using testing::Paint;
using testing::ShadedBall;

// Lamps above (image up, a little toward the camera), a tenth of the light from all round, and
// a floor of the ball's own hue as bright as the ball at half its light: the lit top is brighter
// than the floor, the bottom darker, and a band across the ball has the floor's colour.
I420Image BandedBall(double cx, double cy, double r) {
  const double light[3] = {0.0, -0.8, 0.6};
  return ShadedBall(cx, cy, r, {75.0, 99.0, 164.0}, 0.1, light);
}

TEST(Outline, ABallWhoseShadeCrossesTheFloorsLevelIsFoundByItsOutline) {
  const double cx = 30.3, cy = 24.6, r = 6.0;
  const I420Image image = BandedBall(cx, cy, r);
  // The guess: the lit cap's centre, 2.5 px up. The edge rays from there start in the band of
  // the floor's colour: no fit, or one off by over a pixel.
  const double gx = cx + 0.3, gy = cy - 2.5;
  const auto edge = MeasureEdgeCentre(image.View(), gx, gy, r);
  EXPECT_TRUE(!edge || std::hypot(edge->cx - cx, edge->cy - cy) > 1.0);
  double colour[3];
  ASSERT_TRUE(ColourAt(image.View(), gx, gy, colour));
  const auto fit = FitOutline(image.View(), gx, gy, r, 3.5, colour);
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->cx, cx, 0.25);
  EXPECT_NEAR(fit->cy, cy, 0.25);
  EXPECT_NEAR(fit->radius, r, 0.4);
  EXPECT_GE(fit->share, OutlineOptions{}.min_share);
}

TEST(Outline, AWhiteDiscBesideTheBallDoesNotPullTheOutline) {
  // An orange disc on the blue table and, 3 px beyond its edge, a white one of its size (a lamp,
  // twice the ball's contrast); the guess between them, the shift allowed reaching both.
  const double cx = 24.2, cy = 22.4, r = 5.0, wx = cx + 13.0;
  I420Image image = Paint(64, 48, [&](double x, double y) { return Disc(x, y, cx, cy, r); });
  const I420Image white = Paint(64, 48, [&](double x, double y) { return Disc(x, y, wx, cy, r); },
                                {235.0, 128.0, 128.0});
  for (int y = 0; y < 48; ++y) {
    for (int x = static_cast<int>(wx - r - 1.0); x < 64; ++x) {
      image.y()[y * 64 + x] = white.y()[y * 64 + x];
      image.u()[(y / 2) * 32 + x / 2] = white.u()[(y / 2) * 32 + x / 2];
      image.v()[(y / 2) * 32 + x / 2] = white.v()[(y / 2) * 32 + x / 2];
    }
  }
  double colour[3];
  ASSERT_TRUE(ColourAt(image.View(), cx, cy, colour));
  const double gx = cx + 5.0;
  const auto fit = FitOutline(image.View(), gx, cy, r, 10.0, colour);
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->cx, cx, 0.2);
  EXPECT_NEAR(fit->cy, cy, 0.2);
  // Every normal counted whatever the colour inside it: the white disc's outline wins.
  OutlineOptions any_hue;
  any_hue.max_hue_deg = 180.0;
  const auto pulled = FitOutline(image.View(), gx, cy, r, 10.0, colour, any_hue);
  ASSERT_TRUE(pulled.has_value());
  EXPECT_NEAR(pulled->cx, wx, 0.5);
}

TEST(Outline, NoOutlineForAGreyBallASpeckOrBeyondTheShiftAllowed) {
  const double cx = 30.0, cy = 24.0, r = 5.0;
  const I420Image image = Paint(64, 48, [&](double x, double y) { return Disc(x, y, cx, cy, r); });
  double colour[3];
  ASSERT_TRUE(ColourAt(image.View(), cx, cy, colour));
  // 4 px off: found where 5 px of shift are allowed, not where 2 are.
  const auto far = FitOutline(image.View(), cx - 4.0, cy, r, 5.0, colour);
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(far->cx, cx, 0.2);
  EXPECT_FALSE(FitOutline(image.View(), cx - 4.0, cy, r, 2.0, colour).has_value());
  // A grey ball has no hue to hold the inside to.
  const double grey[3] = {200.0, 130.0, 126.0};
  EXPECT_FALSE(FitOutline(image.View(), cx, cy, r, 2.0, grey).has_value());
  // A speck of half the ball's radius: the contrast peaks at the end of the radii searched.
  const I420Image speck =
      Paint(64, 48, [&](double x, double y) { return Disc(x, y, cx, cy, 0.5 * r); });
  EXPECT_FALSE(FitOutline(speck.View(), cx, cy, r, 2.0, colour).has_value());
  // Nothing there: the blue table alone.
  EXPECT_FALSE(FitOutline(image.View(), 10.0, 10.0, r, 2.0, colour).has_value());
}

TEST(OutlineOptions, Validation) {
  std::string error;
  EXPECT_TRUE(OutlineOptions{}.IsValid(&error));
  OutlineOptions o;
  o.directions = 4;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("directions"), std::string::npos);
  o = {};
  o.fine_px = 2.0;  // coarser than the coarse grid
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.min_share = 1.5;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.max_radius_ratio = 0.9;
  EXPECT_FALSE(o.IsValid(&error));
}

}  // namespace
}  // namespace p4::segment
