#include "p4/segment/blob_finder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "p4/segment/test_images.h"

namespace p4::segment {
namespace {

using testing::Disc;
using testing::Paint;

class BlobFinderTest : public ::testing::Test {
 protected:
  BlobFinderTest() : set_(DefaultOrangeBall()), lut_(set_.BuildLut()) {
    options_.mask = set_.MaskOf("ball");
  }

  int Find(const ImageView& view, const Roi& roi = {}) {
    return finder_.Find(view, lut_, roi, options_, &regions_);
  }

  ColorClassSet set_;
  ColorLut lut_;
  SegmentOptions options_;
  BlobFinder finder_;
  std::vector<Region> regions_;
};

// Repacks an I420 image as NV12 / YUYV (same pixels), with padded strides.
struct Repacked {
  std::vector<uint8_t> y, uv, yuyv;
  ImageView nv12, packed;
};
Repacked Repack(const I420Image& img) {
  Repacked r;
  const int w = img.width(), h = img.height(), stride = w + 16;
  r.y.assign(static_cast<std::size_t>(stride) * h, 0);
  r.uv.assign(static_cast<std::size_t>(stride) * h / 2, 0);
  r.yuyv.assign(static_cast<std::size_t>(2 * w + 8) * h, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const uint8_t yy = img.y()[y * w + x];
      const uint8_t u = img.u()[(y / 2) * (w / 2) + x / 2], v = img.v()[(y / 2) * (w / 2) + x / 2];
      r.y[y * stride + x] = yy;
      r.uv[(y / 2) * stride + (x / 2) * 2] = u;
      r.uv[(y / 2) * stride + (x / 2) * 2 + 1] = v;
      uint8_t* p = &r.yuyv[static_cast<std::size_t>(y) * (2 * w + 8) + (x / 2) * 4];
      p[(x % 2) * 2] = yy;
      p[1] = u;
      p[3] = v;
    }
  }
  r.nv12 = {PixelFormat::kNV12,
            w,
            h,
            {{r.y.data(), w, h, stride}, {r.uv.data(), w / 2, h / 2, stride}, {}}};
  r.packed = {PixelFormat::kYUYV, w, h, {{r.yuyv.data(), w, h, 2 * w + 8}, {}, {}}};
  return r;
}

TEST_F(BlobFinderTest, FindsADiscWithSubpixelCentroidAndDiameter) {
  for (const auto& [cx, cy] :
       {std::pair{40.3, 30.7}, std::pair{41.5, 29.25}, std::pair{40.9, 31.1}}) {
    const double r = 7.0;
    const I420Image img = Paint(96, 64, [&](double x, double y) { return Disc(x, y, cx, cy, r); });
    ASSERT_EQ(Find(img.View()), 1);
    const Region& g = regions_[0];
    EXPECT_NEAR(g.cx, cx, 0.35);
    EXPECT_NEAR(g.cy, cy, 0.35);
    // Edge pixels count when mostly covered (the chroma of a 2x2 block must be orange enough):
    // the binary region is up to ~1.3 px narrower than the disc, never wider.
    EXPECT_NEAR(g.diameter, 2 * r - 0.65, 0.7);
    EXPECT_NEAR(g.minor_diameter, 2 * r - 0.65, 0.7);
    EXPECT_FALSE(g.touches_border);
  }
}

TEST_F(BlobFinderTest, SameRegionsInI420Nv12AndYuyv) {
  const I420Image img = Paint(96, 64, [](double x, double y) {
    return std::max(Disc(x, y, 30.2, 20.6, 6.0), Disc(x, y, 70.0, 44.0, 3.0));
  });
  ASSERT_EQ(Find(img.View()), 2);
  const auto i420 = regions_;
  const Repacked r = Repack(img);
  for (const ImageView& view : {r.nv12, r.packed}) {
    ASSERT_EQ(Find(view), 2);
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(regions_[k].area, i420[k].area);
      EXPECT_DOUBLE_EQ(regions_[k].cx, i420[k].cx);
      EXPECT_DOUBLE_EQ(regions_[k].cy, i420[k].cy);
    }
  }
}

TEST_F(BlobFinderTest, TwoOrangeRegionsComeLargestFirst) {
  const I420Image img = Paint(128, 64, [](double x, double y) {
    return std::max(Disc(x, y, 20.0, 30.0, 4.0), Disc(x, y, 90.0, 30.0, 9.0));
  });
  ASSERT_EQ(Find(img.View()), 2);
  EXPECT_NEAR(regions_[0].cx, 90.0, 0.4);
  EXPECT_NEAR(regions_[1].cx, 20.0, 0.4);
  EXPECT_GT(regions_[0].area, regions_[1].area);
}

// A block mask (what differs from the background) hides what it does not allow: the large
// disc's blocks are masked out, the small one stays, at the same place.
TEST_F(BlobFinderTest, ABlockMaskHidesWhatItDoesNotAllow) {
  const I420Image img = Paint(128, 64, [](double x, double y) {
    return std::max(Disc(x, y, 20.0, 30.0, 4.0), Disc(x, y, 90.0, 30.0, 9.0));
  });
  std::vector<uint8_t> allowed(64 * 32, 1);
  for (int by = 0; by < 32; ++by) {
    for (int bx = 38; bx < 64; ++bx) allowed[by * 64 + bx] = 0;  // x >= 76
  }
  const BlockMask blocks{allowed.data(), 64, 32};
  ASSERT_EQ(finder_.Find(img.View(), lut_, {}, options_, &regions_, &blocks), 1);
  EXPECT_NEAR(regions_[0].cx, 20.0, 0.4);
  EXPECT_NEAR(regions_[0].cy, 30.0, 0.4);
}

TEST_F(BlobFinderTest, BallTouchingTheImageBorder) {
  const I420Image img =
      Paint(64, 48, [](double x, double y) { return Disc(x, y, 1.0, 20.0, 6.0); });
  ASSERT_EQ(Find(img.View()), 1);
  EXPECT_TRUE(regions_[0].touches_border);
  EXPECT_EQ(regions_[0].x0, 0);
  EXPECT_GT(regions_[0].cx, 1.0);  // the visible half's centroid lies inside
}

TEST_F(BlobFinderTest, EmptyFrame) {
  const I420Image img = Paint(64, 48, [](double, double) { return 0.0; });
  EXPECT_EQ(Find(img.View()), 0);
  EXPECT_TRUE(regions_.empty());
  EXPECT_TRUE(finder_.runs().empty());
}

TEST_F(BlobFinderTest, RoiAroundTheBallOutsideTheImageAndMissingIt) {
  const I420Image img =
      Paint(160, 120, [](double x, double y) { return Disc(x, y, 100.4, 60.6, 6.0); });
  ASSERT_EQ(Find(img.View()), 1);
  const Region full = regions_[0];
  ASSERT_EQ(Find(img.View(), Roi::Around(98, 62, 40, 40, 160, 120)), 1);
  EXPECT_DOUBLE_EQ(regions_[0].cx, full.cx);
  EXPECT_EQ(regions_[0].area, full.area);
  EXPECT_EQ(Find(img.View(), Roi::Around(30, 30, 40, 40, 160, 120)), 0);
  // A window entirely outside the image is empty, not the whole image.
  const Roi outside = Roi::Around(500, 500, 40, 40, 160, 120);
  EXPECT_TRUE(outside.empty());
  EXPECT_EQ(finder_.Find(img.View(), lut_, Roi{170, 10, 200, 50}, options_, &regions_), 0);
  // A window cut by the border keeps its inside part.
  const Roi cut = Roi::Around(150, 60, 40, 40, 160, 120);
  EXPECT_EQ(cut.x1, 160);
  EXPECT_EQ(cut.x0, 130);
}

TEST_F(BlobFinderTest, StrideFillsSkippedPixels) {
  const I420Image img =
      Paint(96, 64, [](double x, double y) { return Disc(x, y, 40.3, 30.7, 7.0); });
  ASSERT_EQ(Find(img.View()), 1);
  const Region full = regions_[0];
  for (int stride : {2, 3}) {
    options_.stride = stride;
    ASSERT_EQ(Find(img.View()), 1) << stride;
    EXPECT_NEAR(regions_[0].cy, full.cy, 0.3) << stride;
    EXPECT_NEAR(regions_[0].cx, full.cx, 0.5 * stride) << stride;
    EXPECT_GT(regions_[0].area, 0.75 * full.area) << stride;
    EXPECT_LE(regions_[0].area, full.area) << stride;
  }
}

TEST_F(BlobFinderTest, MinimumAreaDropsSpecks) {
  const I420Image img = Paint(64, 48, [](double x, double y) {
    return (std::abs(x - 10) < 0.6 && std::abs(y - 10) < 0.6) ? 1.0 : Disc(x, y, 40, 24, 5);
  });
  options_.min_area = 8;
  ASSERT_EQ(Find(img.View()), 1);
  EXPECT_NEAR(regions_[0].cx, 40.0, 0.4);
}

TEST_F(BlobFinderTest, MotionBlurKeepsTheMinorDiameter) {
  // A ball of diameter 12 smeared over 30 px along a diagonal: a capsule.
  const I420Image img = Paint(128, 96, [](double x, double y) {
    double best = 0.0;
    for (int k = 0; k <= 30; ++k)
      best = std::max(best, Disc(x, y, 40 + k * 0.8, 30 + k * 0.6, 6.0));
    return best;
  });
  ASSERT_EQ(Find(img.View()), 1);
  EXPECT_NEAR(regions_[0].minor_diameter, 12.0, 1.5);
  EXPECT_GT(regions_[0].major_diameter, 30.0);
  EXPECT_GT(regions_[0].diameter, 14.0);  // the area-equivalent diameter does not hold
}

TEST_F(BlobFinderTest, UShapeIsOneRegion) {
  // Two arms joined only at the bottom: union-find must merge them when the rows meet.
  const I420Image img = Paint(64, 48, [](double x, double y) {
    const bool left = x >= 10 && x < 16 && y >= 5 && y < 40;
    const bool right = x >= 40 && x < 46 && y >= 5 && y < 40;
    const bool bottom = x >= 10 && x < 46 && y >= 34 && y < 40;
    return (left || right || bottom) ? 1.0 : 0.0;
  });
  ASSERT_EQ(Find(img.View()), 1);
  EXPECT_EQ(regions_[0].x0, 10);
  EXPECT_EQ(regions_[0].x1, 46);
}

// Chroma first gives exactly the per-pixel path's runs and regions, for I420 and NV12, whole
// frames and windows at odd offsets, on noisy random blobs (many edges, many small regions).
TEST_F(BlobFinderTest, ChromaFirstIsExactlyThePerPixelPath) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int w = 96 + 2 * (trial % 5), h = 64 + 2 * (trial % 3);
    std::vector<std::array<double, 3>> discs;
    for (int k = 0; k < 12; ++k)
      discs.push_back({pos(rng) * w, pos(rng) * h, 0.5 + 5.0 * pos(rng)});
    I420Image img = Paint(w, h, [&](double x, double y) {
      double a = 0.0;
      for (const auto& d : discs) a = std::max(a, Disc(x, y, d[0], d[1], d[2]));
      return a;
    });
    for (auto& b : img.bytes())
      b = static_cast<uint8_t>(std::clamp(b + static_cast<int>(rng() % 21) - 10, 0, 255));
    const Repacked r = Repack(img);
    for (const ImageView& view : {img.View(), r.nv12}) {
      for (const Roi& roi : {Roi{}, Roi{3, 5, w - 7, h - 4}, Roi{1, 0, 42, 31}}) {
        options_.chroma_first = false;
        const int reference = Find(view, roi);
        const std::vector<segment::Run> runs = finder_.runs();
        const std::vector<Region> expected = regions_;
        options_.chroma_first = true;
        ASSERT_EQ(Find(view, roi), reference);
        ASSERT_EQ(finder_.runs().size(), runs.size());
        for (std::size_t i = 0; i < runs.size(); ++i) {
          EXPECT_EQ(finder_.runs()[i].y, runs[i].y);
          EXPECT_EQ(finder_.runs()[i].x0, runs[i].x0);
          EXPECT_EQ(finder_.runs()[i].x1, runs[i].x1);
        }
        for (int k = 0; k < reference; ++k) {
          EXPECT_EQ(regions_[k].area, expected[k].area);
          EXPECT_DOUBLE_EQ(regions_[k].cx, expected[k].cx);
          EXPECT_DOUBLE_EQ(regions_[k].minor_diameter, expected[k].minor_diameter);
        }
      }
    }
  }
}

TEST(SegmentOptions, Validation) {
  SegmentOptions o;
  std::string error;
  EXPECT_TRUE(o.IsValid(&error));
  o.stride = 5;
  EXPECT_FALSE(o.IsValid(&error));
  o.stride = 1;
  o.mask = 0;
  EXPECT_FALSE(o.IsValid(&error));
}

}  // namespace
}  // namespace p4::segment
