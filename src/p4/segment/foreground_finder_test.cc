// ForegroundFinder's block masks on flat synthetic frames: where the picture differs from the
// background, and a window searched only there.
#include "p4/segment/foreground_finder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"

namespace p4::segment {
namespace {

I420Image Flat(int width, int height, uint8_t luma) {
  I420Image image(width, height);
  std::memset(image.y(), luma, static_cast<std::size_t>(width) * height);
  std::memset(image.u(), 128, static_cast<std::size_t>(width / 2) * (height / 2));
  std::memset(image.v(), 128, static_cast<std::size_t>(width / 2) * (height / 2));
  return image;
}

// A grey 64x48 hall learnt, then a frame with a bright 8x8 square at (20, 16).
struct Scene {
  BackgroundModel background;
  I420Image frame;
  Scene() : background(64, 48, {}), frame(Flat(64, 48, 90)) {
    const I420Image hall = Flat(64, 48, 90);
    for (int k = 0; k < 10; ++k) background.Update(hall.View());
    for (int y = 16; y < 24; ++y) std::memset(frame.y() + y * 64 + 20, 170, 8);
  }
};

TEST(ForegroundFinder, DifferingBlocksWithinMasksOnlyItsWindows) {
  Scene scene;
  ASSERT_TRUE(scene.background.ready());
  ForegroundFinder finder;
  const std::vector<Roi> within{{16, 8, 40, 32}};
  const BlockMask mask = finder.DifferingBlocksWithin(scene.frame.View(), scene.background, within,
                                                      3.0, /*grow=*/false);
  ASSERT_EQ(mask.width, 32);
  ASSERT_EQ(mask.height, 24);
  EXPECT_TRUE(mask.Allows(22, 18));   // the square: differs
  EXPECT_FALSE(mask.Allows(34, 28));  // in the window, as the background
  EXPECT_TRUE(mask.Allows(4, 4));     // outside every window: as it was
  EXPECT_TRUE(mask.Allows(60, 44));
  // Grown by a block, the square's rim is allowed as well.
  const BlockMask grown =
      finder.DifferingBlocksWithin(scene.frame.View(), scene.background, within, 3.0, true);
  EXPECT_TRUE(grown.Allows(18, 14));
  EXPECT_FALSE(grown.Allows(34, 28));
}

TEST(ForegroundFinder, DifferingShareCountsTheBlocksThatDiffer) {
  Scene scene;
  // The 8x8 square is 16 of a 24x24 window's 144 blocks.
  EXPECT_NEAR(
      ForegroundFinder::DifferingShare(scene.frame.View(), scene.background, {12, 8, 36, 32}, 3.0),
      16.0 / 144.0, 1e-9);
  EXPECT_DOUBLE_EQ(
      ForegroundFinder::DifferingShare(scene.frame.View(), scene.background, {40, 30, 64, 48}, 3.0),
      0.0);
  EXPECT_DOUBLE_EQ(
      ForegroundFinder::DifferingShare(scene.frame.View(), scene.background, {10, 10, 10, 20}, 3.0),
      0.0);
}

// Paints the ball's colour over a flat frame where `inside` holds, by each pixel's covered share
// (8x8 samples; the chroma per 2x2 block by the block's share).
void PaintBall(I420Image* frame, const BallColour& ball,
               const std::function<bool(double, double)>& inside) {
  const int width = frame->width(), height = frame->height();
  std::vector<double> share(static_cast<std::size_t>(width) * height, 0.0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int n = 0;
      for (int j = 0; j < 8; ++j) {
        for (int i = 0; i < 8; ++i) n += inside(x - 0.5 + (i + 0.5) / 8, y - 0.5 + (j + 0.5) / 8);
      }
      share[static_cast<std::size_t>(y) * width + x] = n / 64.0;
    }
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t& luma = frame->y()[y * width + x];
      const double a = share[static_cast<std::size_t>(y) * width + x];
      luma = static_cast<uint8_t>(std::lround(luma + a * (ball.lit.y - luma)));
    }
  }
  for (int by = 0; by < height / 2; ++by) {
    for (int bx = 0; bx < width / 2; ++bx) {
      double a = 0.0;
      for (int k = 0; k < 4; ++k) {
        a += 0.25 * share[static_cast<std::size_t>(2 * by + k / 2) * width + 2 * bx + k % 2];
      }
      uint8_t& u = frame->u()[by * (width / 2) + bx];
      uint8_t& v = frame->v()[by * (width / 2) + bx];
      u = static_cast<uint8_t>(std::lround(u + a * (ball.lit.u - u)));
      v = static_cast<uint8_t>(std::lround(v + a * (ball.lit.v - v)));
    }
  }
}

// A grey 96x64 hall learnt; the ball (10 px) at (50.3, 30.6) in the frames the cases paint.
struct DiscScene {
  static constexpr double kX = 50.3, kY = 30.6, kDiameter = 10.0;
  BackgroundModel background;
  I420Image frame;
  BallColour ball = BallColour::Orange();
  DiscScene() : background(96, 64, {}), frame(Flat(96, 64, 90)) {
    const I420Image hall = Flat(96, 64, 90);
    for (int k = 0; k < 10; ++k) background.Update(hall.View());
  }
  static bool InBall(double x, double y) { return std::hypot(x - kX, y - kY) <= 0.5 * kDiameter; }
};

// A ball that meets something of its colour in the image (a sleeve, a line) is one region with
// it; the disc of the ball's known size is found in that region, its centre by its own coverage.
TEST(ForegroundFinderDisc, ABallTouchingASleeveOfItsColourIsFoundByItsSize) {
  DiscScene scene;
  // A sleeve 26 px wide and 20 tall whose right side meets the ball's left edge.
  PaintBall(&scene.frame, scene.ball, [](double x, double y) {
    return DiscScene::InBall(x, y) ||
           (x >= DiscScene::kX - 31.0 && x <= DiscScene::kX - 5.0 && y >= 22.0 && y <= 42.0);
  });
  ForegroundFinder finder;
  const Roi window{20, 10, 70, 52};
  CoverageRegion whole;
  ASSERT_TRUE(finder.Measure(scene.frame.View(), scene.background, scene.ball, window, {}, &whole));
  // Measured as one region, the centre lies in the sleeve.
  EXPECT_GT(std::hypot(whole.region.cx - DiscScene::kX, whole.region.cy - DiscScene::kY), 8.0);
  CoverageRegion disc;
  ASSERT_TRUE(finder.FindDisc(scene.frame.View(), scene.background, scene.ball, DiscScene::kX - 3.0,
                              DiscScene::kY + 2.0, 6.0, DiscScene::kDiameter, {}, {}, &disc));
  EXPECT_NEAR(disc.region.cx, DiscScene::kX, 0.15);
  EXPECT_NEAR(disc.region.cy, DiscScene::kY, 0.15);
  EXPECT_NEAR(disc.region.diameter, DiscScene::kDiameter, 1.0);
}

TEST(ForegroundFinderDisc, ABallAcrossALineOfItsColourIsFoundByItsSize) {
  DiscScene scene;
  // A line 2 px wide through the ball, at 30 degrees.
  PaintBall(&scene.frame, scene.ball, [](double x, double y) {
    const double across = (x - DiscScene::kX) * 0.5 - (y - DiscScene::kY) * 0.866;
    return DiscScene::InBall(x, y) || std::abs(across + 1.5) <= 1.0;
  });
  ForegroundFinder finder;
  CoverageRegion disc;
  ASSERT_TRUE(finder.FindDisc(scene.frame.View(), scene.background, scene.ball, DiscScene::kX + 2.0,
                              DiscScene::kY - 2.0, 6.0, DiscScene::kDiameter, {}, {}, &disc));
  EXPECT_NEAR(disc.region.cx, DiscScene::kX, 0.15);
  EXPECT_NEAR(disc.region.cy, DiscScene::kY, 0.15);
}

TEST(ForegroundFinderDisc, ALargeBallIsCentredFromItsCoarseGrid) {
  // A ball of 26 px (searched every 2 px) touching a sleeve of its colour, 160x120.
  const double x0 = 80.4, y0 = 60.7, d = 26.0;
  BackgroundModel background(160, 120, {});
  const I420Image hall = Flat(160, 120, 90);
  for (int k = 0; k < 10; ++k) background.Update(hall.View());
  I420Image frame = Flat(160, 120, 90);
  const BallColour ball = BallColour::Orange();
  PaintBall(&frame, ball, [&](double x, double y) {
    return std::hypot(x - x0, y - y0) <= 0.5 * d ||
           (x >= x0 - 70.0 && x <= x0 - 0.5 * d && std::abs(y - y0) <= 0.4 * d);
  });
  ForegroundFinder finder;
  CoverageRegion disc;
  ASSERT_TRUE(
      finder.FindDisc(frame.View(), background, ball, x0 + 5.0, y0 - 4.0, 10.0, d, {}, {}, &disc));
  EXPECT_NEAR(disc.region.cx, x0, 0.15);
  EXPECT_NEAR(disc.region.cy, y0, 0.15);
}

TEST(ForegroundFinderDisc, NoDiscStandsOutInsideAShirtOfTheBallsColour) {
  DiscScene scene;
  // The ball wholly inside a shirt of its colour: nothing tells it from the shirt.
  PaintBall(&scene.frame, scene.ball, [](double x, double y) {
    return x >= DiscScene::kX - 20.0 && x <= DiscScene::kX + 20.0 && y >= 8.0 && y <= 56.0;
  });
  ForegroundFinder finder;
  CoverageRegion disc;
  EXPECT_FALSE(finder.FindDisc(scene.frame.View(), scene.background, scene.ball, DiscScene::kX,
                               DiscScene::kY, 6.0, DiscScene::kDiameter, {}, {}, &disc));
  // Nor where nothing differs from the background.
  EXPECT_FALSE(finder.FindDisc(scene.frame.View(), scene.background, scene.ball, 85.0, 50.0, 4.0,
                               DiscScene::kDiameter, {}, {}, &disc));
}

TEST(ForegroundFinderDisc, TheSearchsBoundsAreChecked) {
  std::string error;
  EXPECT_TRUE(DiscSearchOptions{}.IsValid(&error));
  DiscSearchOptions o;
  o.min_fill = 1.5;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("fill"), std::string::npos);
  o = {};
  o.min_ring_px = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
}

// A white ball of 9-10 px before a grey wall, its chroma the wall's (the encoder's half-resolution
// chroma smears a small ball's into its background; found in white tuning 17, camera 1), measured
// with the white learnt in the hall (126/129, a few levels off neutral as the wall's 130/127 is).
// Near neutral the chroma cannot tell the shading: the ball is lit, and covers the disc whole.
TEST(ForegroundFinder, AWhiteBallWithItsWallsChromaIsMeasuredWhole) {
  const auto hall = [] {
    I420Image image = Flat(96, 64, 140);
    std::memset(image.u(), 130, static_cast<std::size_t>(48) * 32);
    std::memset(image.v(), 127, static_cast<std::size_t>(48) * 32);
    return image;
  };
  BackgroundModel background(96, 64, {});
  for (int k = 0; k < 10; ++k) background.Update(hall().View());
  I420Image frame = hall();
  const BallColour seen{{205.0f, 130.0f, 127.0f}};    // as this camera shows it
  const BallColour learnt{{210.0f, 126.0f, 129.0f}};  // as the hall's colours were learnt
  PaintBall(&frame, seen, DiscScene::InBall);
  const double disc = M_PI * 0.25 * DiscScene::kDiameter * DiscScene::kDiameter;
  const Roi window{40, 20, 62, 42};
  ForegroundFinder finder;
  ForegroundOptions options;
  CoverageRegion r;
  ASSERT_TRUE(finder.Measure(frame.View(), background, learnt, window, options, &r));
  // The luma says 0.93-0.97 of a ball lit as learnt (205 of 210 over 140).
  EXPECT_NEAR(r.coverage, 0.93 * disc, 0.08 * disc);
  EXPECT_NEAR(r.region.cx, DiscScene::kX, 0.2);
  EXPECT_NEAR(r.region.cy, DiscScene::kY, 0.2);
  // The shading fitted to those few levels of chroma: the ball's middle is no ball.
  options.unmix.neutral_chroma = 0.0;
  const bool found = finder.Measure(frame.View(), background, learnt, window, options, &r);
  EXPECT_TRUE(!found || r.coverage < 0.5 * disc) << r.coverage;
  std::string error;
  EXPECT_TRUE(ForegroundOptions{}.IsValid(&error));
  options.unmix.neutral_chroma = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("neutral"), std::string::npos);
}

}  // namespace
}  // namespace p4::segment
