// The ball's centre from its edge (ball_edge.h) on painted frames with known centres.
#include "p4/segment/ball_edge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "p4/segment/test_images.h"

namespace p4::segment {
namespace {

using testing::Disc;
using testing::Paint;

TEST(EdgeCentre, ADiscStartedAPixelOffIsCentredToAFewHundredths) {
  const double cx = 30.3, cy = 24.7, r = 5.0;
  const I420Image image = Paint(64, 48, [&](double x, double y) { return Disc(x, y, cx, cy, r); });
  const auto e = MeasureEdgeCentre(image.View(), cx - 1.0, cy + 0.8, r);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->cx, cx, 0.05);
  EXPECT_NEAR(e->cy, cy, 0.05);
  EXPECT_EQ(e->pairs, EdgeCentreOptions{}.directions / 2);
}

TEST(EdgeCentre, ShadingInsideTheDiscAndALineBeyondItDoNotMoveTheCentre) {
  // The ball's luma falls from its lit top to a dark bottom (still above the table's); a white
  // line runs 2 px below it.
  const double cx = 30.0, cy = 20.4, r = 5.0;
  I420Image image = Paint(64, 48, [&](double x, double y) { return Disc(x, y, cx, cy, r); });
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      uint8_t& luma = image.y()[y * 64 + x];
      const double a = Disc(x, y, cx, cy, r);
      const double shade = 1.0 - 0.45 * std::clamp((y - cy + r) / (2.0 * r), 0.0, 1.0);
      const double line = (y == 28 || y == 29) ? 1.0 : 0.0;
      luma =
          static_cast<uint8_t>(std::lround(a * 137.0 * shade + (1.0 - a) * (line ? 220.0 : 44.0)));
    }
  }
  const auto e = MeasureEdgeCentre(image.View(), cx + 0.6, cy - 0.9, r);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->cx, cx, 0.1);
  EXPECT_NEAR(e->cy, cy, 0.15);
}

// An orange ball lit from above over a red-brown floor as dark as its shaded bottom
// (testing::ShadedBall's defaults): the half-level edge comes early at the bottom.
I420Image ShadedBall(double cx, double cy, double r) { return testing::ShadedBall(cx, cy, r); }

TEST(EdgeCentre, TheShadedSideIsFaintAndTheKnownWidthMovesTheCentreBack) {
  const double cx = 30.2, cy = 24.6, r = 4.5;
  const I420Image image = ShadedBall(cx, cy, r);
  const auto e = MeasureEdgeCentre(image.View(), cx + 0.5, cy - 0.5, r);
  ASSERT_TRUE(e.has_value());
  // The bottom (image +y) is the faint side; the edge there came early: the centre is high and
  // the width short.
  EXPECT_GT(e->faint[1], 0.9);
  const double raw = std::hypot(e->cx - cx, e->cy - cy);
  EXPECT_LT(e->cy, cy - 0.15);
  EXPECT_LT(e->minor_diameter, 2.0 * r - 0.5);
  // The ball's width known (from the point other views place it at): the centre moved back.
  double ux = e->cx, uy = e->cy;
  UnshadeCentre(e->minor_diameter, e->faint, 2.0 * r, {}, &ux, &uy);
  EXPECT_LT(std::hypot(ux - cx, uy - cy), 0.5 * raw);
  EXPECT_NEAR(uy, cy, 0.1);
  // Not known, or no width lost: the centre stays.
  double sx = e->cx, sy = e->cy;
  UnshadeCentre(e->minor_diameter, e->faint, 0.0, {}, &sx, &sy);
  UnshadeCentre(2.0 * r, e->faint, 2.0 * r, {}, &sx, &sy);
  EXPECT_EQ(sx, e->cx);
  EXPECT_EQ(sy, e->cy);
}

TEST(EdgeCentre, TheWidthsOfADiscAndOfATiltedEllipse) {
  const double cx = 30.3, cy = 24.7;
  const I420Image disc = Paint(64, 48, [&](double x, double y) { return Disc(x, y, cx, cy, 5.0); });
  const auto d = MeasureEdgeCentre(disc.View(), cx, cy, 5.0);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->minor_diameter, 10.0, 0.2);
  EXPECT_NEAR(d->major_diameter, 10.0, 0.2);
  // Semi-axes 6.5 and 4.5 px, the long one 30 degrees from x (a short blur streak's shape).
  const double c = std::cos(M_PI / 6.0), s = std::sin(M_PI / 6.0);
  const I420Image ellipse = Paint(64, 48, [&](double x, double y) {
    // Coverage by 4x4 subsamples of the pixel.
    double hit = 0.0;
    for (int k = 0; k < 16; ++k) {
      const double u = x + (k % 4 + 0.5) / 4.0 - 0.5 - cx, v = y + (k / 4 + 0.5) / 4.0 - 0.5 - cy;
      const double a = c * u + s * v, b = -s * u + c * v;
      hit += (a * a) / (6.5 * 6.5) + (b * b) / (4.5 * 4.5) <= 1.0 ? 1.0 : 0.0;
    }
    return hit / 16.0;
  });
  const auto e = MeasureEdgeCentre(ellipse.View(), cx, cy, 6.5);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->minor_diameter, 9.0, 0.3);
  EXPECT_NEAR(e->major_diameter, 13.0, 0.5);
}

TEST(EdgeCentre, NothingToMeasure) {
  const I420Image flat = Paint(64, 48, [](double, double) { return 0.0; });
  EXPECT_FALSE(MeasureEdgeCentre(flat.View(), 30.0, 24.0, 5.0).has_value());
  // At the image's border the rays leave the picture.
  const I420Image border =
      Paint(64, 48, [](double x, double y) { return Disc(x, y, 2.0, 24.0, 5.0); });
  EXPECT_FALSE(MeasureEdgeCentre(border.View(), 2.0, 24.0, 5.0).has_value());
}

// A ball of 12 px merged on its left with a region of its colour (a sleeve): the rays that end
// there find no edge or the sleeve's; the circle from single rays finds the centre and the width
// from the outline's other 290 degrees.
double Sleeve(double x, double y, double cx, double cy, double r) {
  const bool in = x >= cx - r - 9.0 && x <= cx - 0.5 * r && std::abs(y - cy) <= 0.6 * r;
  return std::max(Disc(x, y, cx, cy, r), in ? 1.0 : 0.0);
}

TEST(EdgeCircle, ABallMergedWithARegionOfItsColourOnOneSide) {
  const double cx = 34.3, cy = 24.7, r = 6.0;
  const I420Image image =
      Paint(72, 48, [&](double x, double y) { return Sleeve(x, y, cx, cy, r); });
  // The pair fit leans to the sleeve (0.6 px here: the pairs through its ends agree with it).
  const auto pair = MeasureEdgeCentre(image.View(), cx + 1.0, cy - 0.8, r);
  EXPECT_TRUE(!pair || std::hypot(pair->cx - cx, pair->cy - cy) > 0.4);
  const auto e = MeasureEdgeCircle(image.View(), cx + 1.0, cy - 0.8, r);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->cx, cx, 0.1);
  EXPECT_NEAR(e->cy, cy, 0.1);
  EXPECT_NEAR(e->minor_diameter, 2.0 * r, 0.3);
  EXPECT_EQ(e->minor_diameter, e->major_diameter);
  // A whole disc: the same centre as the pair fit.
  const I420Image disc = Paint(72, 48, [&](double x, double y) { return Disc(x, y, cx, cy, r); });
  const auto whole = MeasureEdgeCircle(disc.View(), cx - 1.0, cy + 0.8, r);
  ASSERT_TRUE(whole.has_value());
  EXPECT_NEAR(whole->cx, cx, 0.1);
  EXPECT_NEAR(whole->cy, cy, 0.1);
  EXPECT_EQ(whole->pairs, EdgeCircleOptions{}.edge.directions);
}

TEST(EdgeCircle, NoCircleOnABarOrWhereLessThanHalfTheOutlineShows) {
  // A bar of the ball's colour, 4 px wide: rays along it find no edge.
  const I420Image bar = Paint(72, 48, [](double x, double y) {
    return std::abs(y - 24.0) <= 2.0 && x > 5.0 && x < 67.0 ? 1.0 : 0.0;
  });
  EXPECT_FALSE(MeasureEdgeCircle(bar.View(), 36.0, 24.0, 5.0).has_value());
  // A ball whose whole left half is merged with a wide region: the gap is over 180 degrees.
  const double cx = 34.0, cy = 24.0, r = 6.0;
  const I420Image half = Paint(72, 48, [&](double x, double y) {
    return std::max(Disc(x, y, cx, cy, r),
                    x <= cx - 0.2 * r && std::abs(y - cy) <= 1.1 * r ? 1.0 : 0.0);
  });
  EXPECT_FALSE(MeasureEdgeCircle(half.View(), cx, cy, r).has_value());
  const I420Image flat = Paint(72, 48, [](double, double) { return 0.0; });
  EXPECT_FALSE(MeasureEdgeCircle(flat.View(), 36.0, 24.0, 5.0).has_value());
}

TEST(EdgeCentreOptions, Validation) {
  EXPECT_TRUE(EdgeCentreOptions{}.IsValid(nullptr));
  EdgeCentreOptions odd;
  odd.directions = 31;
  std::string error;
  EXPECT_FALSE(odd.IsValid(&error));
  EXPECT_FALSE(error.empty());
  EdgeCentreOptions share;
  share.min_pair_share = 1.5;
  EXPECT_FALSE(share.IsValid(nullptr));
  EXPECT_TRUE(ShadeOptions{}.IsValid(nullptr));
  EXPECT_FALSE((ShadeOptions{0.3, 1.0}.IsValid(&error)));
  EXPECT_FALSE((ShadeOptions{-0.1, 0.25}.IsValid(nullptr)));
  EXPECT_FALSE((ShadeOptions{0.3, 0.25, -1, 0.8}.IsValid(nullptr)));
  EXPECT_FALSE((ShadeOptions{0.3, 0.25, 10, 0.0}.IsValid(nullptr)));
  EXPECT_FALSE((ShadeOptions{0.3, 0.25, 10, 1.5}.IsValid(nullptr)));
  EXPECT_TRUE(EdgeCircleOptions{}.IsValid(nullptr));
  EdgeCircleOptions circle;
  circle.max_gap_deg = 200.0;
  EXPECT_FALSE(circle.IsValid(&error));
  circle = {};
  circle.min_ray_share = 0.0;
  EXPECT_FALSE(circle.IsValid(nullptr));
}

// Lit from above, a camera's views are faint below (image y down) give or take their
// backgrounds: once 10 agree the side is known; views whose faint sides point every way (no
// one light) agree on none.
TEST(FaintSideVote, ACamerasViewsAgreeOnTheHallsFaintSide) {
  const ShadeOptions options;  // 10 views, mean length 0.8
  FaintSideVote vote;
  double side[2] = {0.0, 0.0};
  const double none[2] = {0.0, 0.0};
  for (int k = 0; k < 9; ++k) {
    const double a = M_PI / 2 + 0.3 * std::sin(k);  // about straight down, +-17 degrees
    const double f[2] = {std::cos(a), std::sin(a)};
    vote.Add(f);
    vote.Add(none);  // a view with no faint side is no vote
  }
  EXPECT_FALSE(vote.Agreed(options, side));
  EXPECT_EQ(side[0], 0.0);
  const double down[2] = {0.0, 2.0};  // not unit: counted as one unit vote
  vote.Add(down);
  ASSERT_TRUE(vote.Agreed(options, side));
  EXPECT_NEAR(std::hypot(side[0], side[1]), 1.0, 1e-12);
  EXPECT_NEAR(std::atan2(side[1], side[0]), M_PI / 2, 0.1);
  ShadeOptions off = options;
  off.camera_min_views = 0;
  EXPECT_FALSE(vote.Agreed(off, side));

  FaintSideVote scattered;
  for (int k = 0; k < 40; ++k) {
    const double a = 2.0 * M_PI * k / 7.0;
    const double f[2] = {std::cos(a), std::sin(a)};
    scattered.Add(f);
  }
  EXPECT_FALSE(scattered.Agreed(options, side));
}

}  // namespace
}  // namespace p4::segment
