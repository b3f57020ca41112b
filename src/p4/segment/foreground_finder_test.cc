// ForegroundFinder's block masks on flat synthetic frames: where the picture differs from the
// background, and a window searched only there.
#include "p4/segment/foreground_finder.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/background_model.h"

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
  EXPECT_NEAR(ForegroundFinder::DifferingShare(scene.frame.View(), scene.background,
                                               {12, 8, 36, 32}, 3.0),
              16.0 / 144.0, 1e-9);
  EXPECT_DOUBLE_EQ(
      ForegroundFinder::DifferingShare(scene.frame.View(), scene.background, {40, 30, 64, 48}, 3.0),
      0.0);
  EXPECT_DOUBLE_EQ(
      ForegroundFinder::DifferingShare(scene.frame.View(), scene.background, {10, 10, 10, 20}, 3.0),
      0.0);
}

}  // namespace
}  // namespace p4::segment
