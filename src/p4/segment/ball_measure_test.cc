#include "p4/segment/ball_measure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "p4/segment/test_images.h"

namespace p4::segment {
namespace {

using testing::Disc;
using testing::Paint;

class MeasureBall : public ::testing::Test {
 protected:
  MeasureBall() : set_(DefaultOrangeBall()), lut(set_.BuildLut()) {
    options.mask = set_.MaskOf("ball");
  }
  ColorClassSet set_;
  ColorLut lut;
  SegmentOptions options;
  BlobFinder finder;
  std::vector<Region> regions;
};

TEST_F(MeasureBall, DiameterAndCentreOnTwoBackgrounds) {
  // On the blue table and on a red-brown floor (whose chroma is close to the ball's).
  for (const testing::Yuv background : {testing::kTableBlue, testing::Yuv{65.0, 115.0, 150.0}}) {
    for (const double r : {3.5, 5.0, 8.0}) {
      const double cx = 40.37, cy = 30.81;
      I420Image img = Paint(
          96, 64, [&](double x, double y) { return Disc(x, y, cx, cy, r); }, testing::kOrange,
          background);
      // Sensor noise (sigma 2) and faint floor boards (4 levels) on the luma.
      std::mt19937 rng(static_cast<unsigned>(r * 10));
      std::normal_distribution<double> noise(0.0, 2.0);
      for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 96; ++x) {
          const double board = (y / 6) % 2 ? 4.0 : 0.0;
          img.y()[y * 96 + x] = static_cast<uint8_t>(
              std::clamp(img.y()[y * 96 + x] + noise(rng) + board, 0.0, 255.0));
        }
      }
      ASSERT_EQ(finder.Find(img.View(), lut, {}, options, &regions), 1);
      const auto m = segment::MeasureBall(img.View(), regions[0]);
      ASSERT_TRUE(m.has_value());
      EXPECT_NEAR(m->diameter, 2 * r, 0.4) << r;
      EXPECT_NEAR(m->minor_diameter, 2 * r, 0.5) << r;
      EXPECT_NEAR(m->cx, cx, 0.15);
      EXPECT_NEAR(m->cy, cy, 0.15);
      EXPECT_GT(m->contrast, 50.0);
    }
  }
}

TEST_F(MeasureBall, NoMeasureAtTheBorderOrWithoutContrast) {
  const I420Image edge =
      Paint(64, 48, [](double x, double y) { return Disc(x, y, 2.0, 20.0, 5.0); });
  ASSERT_EQ(finder.Find(edge.View(), lut, {}, options, &regions), 1);
  EXPECT_FALSE(segment::MeasureBall(edge.View(), regions[0]).has_value());
  // Same luma as the background: only chroma tells them apart.
  const I420Image flat = Paint(
      64, 48, [](double x, double y) { return Disc(x, y, 30.0, 20.0, 5.0); }, testing::kOrange,
      testing::Yuv{137.0, 128.0, 128.0});
  ASSERT_EQ(finder.Find(flat.View(), lut, {}, options, &regions), 1);
  EXPECT_FALSE(segment::MeasureBall(flat.View(), regions[0]).has_value());
}

}  // namespace
}  // namespace p4::segment
