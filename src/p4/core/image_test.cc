#include "p4/core/image.h"

#include <gtest/gtest.h>

#include <vector>

#include "p4/core/table.h"
#include "p4/core/time.h"

namespace p4 {
namespace {

TEST(I420Image, PlanesAreContiguousAndSized) {
  I420Image image(8, 4);
  EXPECT_EQ(image.bytes().size(), 8u * 4u * 3u / 2u);
  EXPECT_EQ(image.u() - image.y(), 32);
  EXPECT_EQ(image.v() - image.u(), 8);
  const ImageView view = image.View();
  EXPECT_EQ(view.planes[1].width, 4);
  EXPECT_EQ(view.planes[1].height, 2);
  EXPECT_EQ(view.planes[2].Row(1), image.v() + 4);
}

// A frame whose Y is 10 x + y and whose chroma encodes its own position, in the three formats:
// the downsampled I420 holds the samples at factor x (row, column), the same from each.
TEST(DownsampleToI420, SamplesEveryFormatAlike) {
  const int w = 16, h = 8;
  I420Image i420(w, h);
  std::vector<uint8_t> nv12(w * h * 3 / 2), yuyv(w * h * 2);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const uint8_t luma = static_cast<uint8_t>(10 * x + y);
      i420.y()[y * w + x] = luma;
      nv12[y * w + x] = luma;
      yuyv[y * 2 * w + 2 * x] = luma;
      const uint8_t cu = static_cast<uint8_t>(100 + x / 2), cv = static_cast<uint8_t>(200 + y);
      if (y % 2 == 0 && x % 2 == 0) {
        i420.u()[(y / 2) * (w / 2) + x / 2] = cu;
        i420.v()[(y / 2) * (w / 2) + x / 2] = cv;
        nv12[w * h + (y / 2) * w + x] = cu;
        nv12[w * h + (y / 2) * w + x + 1] = cv;
      }
      if (x % 2 == 0) {
        yuyv[y * 2 * w + 2 * x + 1] = cu;
        yuyv[y * 2 * w + 2 * x + 3] = cv;
      }
    }
  }
  ImageView v_nv12{
      PixelFormat::kNV12, w, h, {{nv12.data(), w, h, w}, {nv12.data() + w * h, w / 2, h / 2, w}}};
  ImageView v_yuyv{PixelFormat::kYUYV, w, h, {{yuyv.data(), w, h, 2 * w}}};
  for (const ImageView& view : {i420.View(), v_nv12, v_yuyv}) {
    I420Image out;
    DownsampleToI420(view, 2, &out);
    ASSERT_EQ(out.width(), 8);
    ASSERT_EQ(out.height(), 4);
    EXPECT_EQ(out.y()[1 * 8 + 3], 10 * 6 + 2);  // source (x 6, y 2)
    EXPECT_EQ(out.u()[1 * 4 + 2], 100 + 4);     // chroma of source x 8, y 4
    EXPECT_EQ(out.v()[1 * 4 + 2], 200 + 4);
  }
}

TEST(Time, SecondsRoundTrip) {
  EXPECT_EQ(FromSeconds(1.5), 1'500'000'000);
  EXPECT_DOUBLE_EQ(ToSeconds(FromSeconds(12.345678901)), 12.345678901);
}

TEST(Table, SidesAndSurface) {
  EXPECT_EQ(table::SideOf(-0.1), 'A');
  EXPECT_EQ(table::SideOf(0.1), 'B');
  EXPECT_TRUE(table::OnSurface(1.37, 0.7625));
  EXPECT_FALSE(table::OnSurface(1.38, 0.0));
  // The net: below its top plus a radius, between the posts (plus the margins asked for).
  EXPECT_TRUE(table::MeetsNet(0.0, 0.17, table::kBallRadius));
  EXPECT_FALSE(table::MeetsNet(0.0, 0.175, table::kBallRadius));
  EXPECT_FALSE(table::MeetsNet(0.0, 0.17, table::kBallRadius, -0.005));
  EXPECT_FALSE(table::MeetsNet(0.0, -0.01, table::kBallRadius));
  EXPECT_TRUE(table::MeetsNet(-0.91, 0.05, table::kBallRadius));
  EXPECT_FALSE(table::MeetsNet(0.93, 0.05, table::kBallRadius));
  EXPECT_TRUE(table::MeetsNet(0.93, 0.05, table::kBallRadius, 0.0, table::kBallRadius));
}

}  // namespace
}  // namespace p4
