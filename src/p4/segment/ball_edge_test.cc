// The ball's centre from its edge (ball_edge.h) on painted frames with known centres.
#include "p4/segment/ball_edge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

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
}

}  // namespace
}  // namespace p4::segment
