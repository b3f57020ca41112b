#include "p4/track/epipolar_search.h"

#include <gtest/gtest.h>

#include "p4/core/table.h"
#include "p4/geometry/sphere_depth.h"
#include "p4/geometry/test_cameras.h"
#include "p4/segment/test_images.h"

namespace p4::track {
namespace {

using segment::testing::Disc;
using segment::testing::Paint;
using segment::testing::Yuv;

constexpr Yuv kLitYellow{170.0, 60.0, 150.0};
constexpr Yuv kDimYellow{85.0, 95.0, 139.0};  // the same hue, half the light
constexpr Yuv kDarkRed{50.0, 120.0, 160.0};

class EpipolarSearchTest : public ::testing::Test {
 protected:
  EpipolarSearchTest()
      : a_(p4::testing::MakeCamera("side", {0.2, -3.5, 1.5})),
        b_(p4::testing::MakeCamera("end", {-4.0, -0.8, 2.0}, {0.3, 0.0, 0.0},
                                   {-0.12, 0.05, 0.001, -0.0005, 0.0})) {
    PlaceBall({0.5, 0.2, 0.25});
  }

  // The ball at `ball` (world, m): its views in both cameras.
  void PlaceBall(const Eigen::Vector3d& ball) {
    ball_ = ball;
    pixel_a_ = *a_.Project(ball_);
    diameter_a_ = SphereDiameterPx(a_, ball_, table::kBallRadius);
    pixel_b_ = *b_.Project(ball_);
    radius_b_ = 0.5 * SphereDiameterPx(b_, ball_, table::kBallRadius);
  }

  // Camera b's image: a disc of `colour` and radius scale * the ball's at `at` on dark red.
  I420Image ImageB(const Eigen::Vector2d& at, double scale, Yuv colour) const {
    const double r = scale * radius_b_;
    return Paint(
        b_.width, b_.height, [&](double x, double y) { return Disc(x, y, at.x(), at.y(), r); },
        colour, kDarkRed);
  }

  std::optional<EpipolarFind> Search(const I420Image& image) const {
    const double colour[3] = {kLitYellow.y, kLitYellow.u, kLitYellow.v};
    return SearchAlongEpipolar(a_, pixel_a_, diameter_a_, colour, b_, image.View());
  }

  Camera a_, b_;
  Eigen::Vector3d ball_;
  Eigen::Vector2d pixel_a_, pixel_b_;
  double diameter_a_ = 0.0, radius_b_ = 0.0;
};

TEST_F(EpipolarSearchTest, FindsADimBallOfTheSameHueOnTheSegment) {
  const auto found = Search(ImageB(pixel_b_, 1.0, kDimYellow));
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->pixel - pixel_b_).norm(), 0.3);
  EXPECT_NEAR(found->diameter_px, 2.0 * radius_b_, 0.1 * radius_b_);
  EXPECT_LT((found->point - ball_).norm(), 0.01);
  EXPECT_GT(found->fits, 1);
}

TEST_F(EpipolarSearchTest, FindsItWhereTheFirstViewsDiameterIsTenPerCentOff) {
  diameter_a_ *= 1.1;  // its depth 10 % short: the ball still lies on the segment searched
  const auto found = Search(ImageB(pixel_b_, 1.0, kDimYellow));
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->pixel - pixel_b_).norm(), 0.3);
}

TEST_F(EpipolarSearchTest, FindsABallMergedOnOneSideWithARegionOfItsColour) {
  // Camera b sees the ball against a sleeve of its hue that covers its outline's left quarter and
  // runs far beyond it: no fit of opposite ray pairs holds there; the circle from single rays
  // finds it (and nothing without it).
  PlaceBall({-1.5, -0.4, 0.8});  // nearer camera b: the ball 14 px wide there
  ASSERT_GE(2.0 * radius_b_, EpipolarSearchOptions{}.circle_min_diameter_px);
  const double r = radius_b_;
  const I420Image image = Paint(
      b_.width, b_.height,
      [&](double x, double y) {
        const bool sleeve = x >= pixel_b_.x() - r - 40.0 && x <= pixel_b_.x() - 0.5 * r &&
                            std::abs(y - pixel_b_.y()) <= 0.75 * r;
        return std::max(Disc(x, y, pixel_b_.x(), pixel_b_.y(), r), sleeve ? 1.0 : 0.0);
      },
      kDimYellow, kDarkRed);
  const auto found = Search(image);
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->pixel - pixel_b_).norm(), 0.3);
  EXPECT_LT((found->point - ball_).norm(), 0.01);
  EpipolarSearchOptions pairs_only;
  pairs_only.circle_min_diameter_px = 0.0;
  const double colour[3] = {kLitYellow.y, kLitYellow.u, kLitYellow.v};
  EXPECT_FALSE(
      SearchAlongEpipolar(a_, pixel_a_, diameter_a_, colour, b_, image.View(), pairs_only));
}

TEST_F(EpipolarSearchTest, AnotherHueIsNotTheBall) {
  EXPECT_FALSE(Search(ImageB(pixel_b_, 1.0, {90.0, 160.0, 110.0})).has_value());  // blue
}

TEST_F(EpipolarSearchTest, TwiceTheSizeIsNotTheBall) {
  EXPECT_FALSE(Search(ImageB(pixel_b_, 2.0, kDimYellow)).has_value());
}

TEST_F(EpipolarSearchTest, ABallOffTheEpipolarLineIsNotIt) {
  // 12 px across the line (the line's direction from two points of the ray).
  const Eigen::Vector3d ray = a_.RayDirection(pixel_a_);
  const Eigen::Vector2d along =
      (*b_.Project(ball_ + 0.2 * ray) - *b_.Project(ball_ - 0.2 * ray)).normalized();
  const Eigen::Vector2d across(-along.y(), along.x());
  EXPECT_FALSE(Search(ImageB(pixel_b_ + 12.0 * across, 1.0, kDimYellow)).has_value());
}

TEST_F(EpipolarSearchTest, ABallBeyondTheDepthsItsDiameterAllowsIsNotIt) {
  // The ball's image in b where the ray lies at twice the depth: the first view's diameter says
  // it is not that far.
  const Eigen::Vector3d far = a_.Center() + 2.0 * (ball_ - a_.Center());
  EXPECT_FALSE(Search(ImageB(*b_.Project(far), 1.0, kDimYellow)).has_value());
}

TEST_F(EpipolarSearchTest, TwoBallsOnTheSegmentAreNeither) {
  // A second disc of the ball's size and hue on the same line, 15 % farther along the ray.
  const Eigen::Vector3d farther = a_.Center() + 1.15 * (ball_ - a_.Center());
  const Eigen::Vector2d second = *b_.Project(farther);
  ASSERT_GT((second - pixel_b_).norm(), 4.0 * radius_b_);
  I420Image image = Paint(
      b_.width, b_.height,
      [&](double x, double y) {
        return std::max(Disc(x, y, pixel_b_.x(), pixel_b_.y(), radius_b_),
                        Disc(x, y, second.x(), second.y(), radius_b_));
      },
      kDimYellow, kDarkRed);
  EXPECT_FALSE(Search(image).has_value());
  EXPECT_TRUE(Search(ImageB(second, 1.0, kDimYellow)).has_value());  // alone, it would do
}

TEST_F(EpipolarSearchTest, AWhiteBallIsSearchedForOnlyWhenAsked) {
  const I420Image image = ImageB(pixel_b_, 1.0, {120.0, 127.0, 129.0});  // a white ball in shade
  const double white[3] = {215.0, 128.0, 127.0};
  EXPECT_FALSE(SearchAlongEpipolar(a_, pixel_a_, diameter_a_, white, b_, image.View()).has_value());
  EpipolarSearchOptions grey;
  grey.grey_balls = true;
  const auto found = SearchAlongEpipolar(a_, pixel_a_, diameter_a_, white, b_, image.View(), grey);
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->pixel - pixel_b_).norm(), 0.3);
}

TEST(SameHue, ShadingKeepsTheHueAndGreyWantsGrey) {
  const double lit[3] = {170.0, 60.0, 150.0}, dim[3] = {85.0, 95.0, 139.0};
  const double white[3] = {220.0, 126.0, 131.0}, grey[3] = {90.0, 130.0, 127.0};
  const double blue[3] = {90.0, 160.0, 110.0};
  EXPECT_TRUE(SameHue(lit, dim, 8.0, 30.0));
  EXPECT_TRUE(SameHue(white, grey, 8.0, 30.0));
  EXPECT_FALSE(SameHue(lit, blue, 8.0, 30.0));
  EXPECT_FALSE(SameHue(white, lit, 8.0, 30.0));
  EXPECT_FALSE(SameHue(lit, white, 8.0, 30.0));
}

TEST(EpipolarSearchOptions, RejectsNonsense) {
  std::string error;
  EpipolarSearchOptions o;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  o.depth_ratio = 1.0;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.max_hue_deg = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.max_z = o.floor_z;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.circle_min_diameter_px = -1.0;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.circle.max_gap_deg = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
}

}  // namespace
}  // namespace p4::track
