#include "p4/core/image.h"

#include <gtest/gtest.h>

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

TEST(Time, SecondsRoundTrip) {
  EXPECT_EQ(FromSeconds(1.5), 1'500'000'000);
  EXPECT_DOUBLE_EQ(ToSeconds(FromSeconds(12.345678901)), 12.345678901);
}

TEST(Table, SidesAndSurface) {
  EXPECT_EQ(table::SideOf(-0.1), 'A');
  EXPECT_EQ(table::SideOf(0.1), 'B');
  EXPECT_TRUE(table::OnSurface(1.37, 0.7625));
  EXPECT_FALSE(table::OnSurface(1.38, 0.0));
}

}  // namespace
}  // namespace p4
