#include "p4/segment/colour_learning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace p4::segment {
namespace {

using Paint = std::function<YuvSample(int, int)>;

I420Image Painted(int w, int h, const Paint& colour) {
  I420Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) image.y()[y * w + x] = colour(x, y).y;
  }
  for (int y = 0; y < h / 2; ++y) {
    for (int x = 0; x < w / 2; ++x) {
      const YuvSample s = colour(2 * x, 2 * y);
      image.u()[y * (w / 2) + x] = s.u;
      image.v()[y * (w / 2) + x] = s.v;
    }
  }
  return image;
}

// A shade of the ball's lit colour along the line from black (ball_colour.h).
YuvSample Shaded(double shade) {
  const auto on = [&](double lit, double black) {
    return static_cast<uint8_t>(std::lround(black + shade * (lit - black)));
  };
  return {on(150, 16), on(70, 128), on(200, 128)};
}

constexpr YuvSample kHall{120, 140, 120};
// Skin in the shade: as dark as the ball's core at shade 0.66, a few levels off its colour
// (Shaded(0.66) is 104 90 176).
constexpr YuvSample kArm{104, 95, 168};

struct Frames {
  static constexpr int kW = 160, kH = 120;
  static constexpr double kBallX = 40.5, kBallY = 60.5, kRadius = 7.0;

  Frames() : background(kW, kH, {}) {
    const I420Image hall = Painted(kW, kH, [](int, int) { return kHall; });
    while (!background.ready()) background.Update(hall.View());
    // A ball lit from above (bright top, shade 0.45 at the bottom) and an arm beside it.
    picture = Painted(kW, kH, [](int x, int y) {
      const double dx = x - kBallX, dy = y - kBallY;
      if (dx * dx + dy * dy <= kRadius * kRadius) return Shaded(0.725 - 0.275 * dy / kRadius);
      if (x >= 90 && x < 130 && y >= 40 && y < 70) return kArm;
      return kHall;
    });
  }
  BackgroundModel background;
  I420Image picture;
};

double Taken(const LearnedColour& learnt, YuvSample s) {
  return learnt.classes.BuildLut().Classify(s.y, s.u, s.v) != 0 ? 1.0 : 0.0;
}

TEST(ColourLearning, TheBoxesGiveUpTheColoursOfAnArmThatMovesBesideTheBall) {
  const Frames f;
  ColourLearningOptions options;
  options.min_samples = 20;
  ColourSamples ball_only, with_moving;
  const Eigen::Vector2d centre(Frames::kBallX, Frames::kBallY);
  const std::vector<Eigen::Vector2d> balls = {centre};
  for (int k = 0; k < 10; ++k) {
    ball_only.AddDisc(f.picture.View(), centre, 2.0 * Frames::kRadius, options, &f.background);
    with_moving.AddDisc(f.picture.View(), centre, 2.0 * Frames::kRadius, options, &f.background);
    with_moving.AddMoving(f.picture.View(), f.background, balls, 4.0 * Frames::kRadius, options);
  }
  // The arm's pixels: a 40 x 30 box sampled every 4th pixel both ways, ten times.
  EXPECT_EQ(with_moving.moving(), 10 * 10 * 8);
  LearnedColour plain, learnt;
  std::string why;
  ASSERT_TRUE(ball_only.Learn(options, &plain, &why)) << why;
  ASSERT_TRUE(with_moving.Learn(options, &learnt, &why)) << why;
  // The ball's shaded half and the arm share a colour: the classes drawn along the shading line
  // take the arm...
  EXPECT_EQ(Taken(plain, kArm), 1.0);
  EXPECT_GT(learnt.moving_taken_before, 0.99);
  // ...until they give it up, losing at most a fifth of the ball's pixels and none of its core's
  // colours (the core, shades 0.63-0.82, is what was sampled).
  EXPECT_EQ(Taken(learnt, kArm), 0.0);
  EXPECT_LT(learnt.moving_taken, 0.01);
  EXPECT_LE(learnt.ball_lost, options.max_ball_loss + 1e-9);
  EXPECT_EQ(Taken(learnt, Shaded(0.8)), 1.0);
  EXPECT_EQ(Taken(learnt, Shaded(0.7)), 1.0);
}

TEST(ColourLearning, NothingIsGivenUpWhenWhatMovesHasOtherColours) {
  const Frames f;
  ColourLearningOptions options;
  options.min_samples = 20;
  // A blue shirt moves where the arm was.
  const I420Image picture = Painted(Frames::kW, Frames::kH, [&](int x, int y) {
    if (x >= 90 && x < 130 && y >= 40 && y < 70) return YuvSample{60, 180, 100};
    return YuvSample{f.picture.y()[y * Frames::kW + x],
                     f.picture.u()[(y / 2) * (Frames::kW / 2) + x / 2],
                     f.picture.v()[(y / 2) * (Frames::kW / 2) + x / 2]};
  });
  ColourSamples samples;
  const Eigen::Vector2d centre(Frames::kBallX, Frames::kBallY);
  const std::vector<Eigen::Vector2d> balls = {centre};
  for (int k = 0; k < 10; ++k) {
    samples.AddDisc(picture.View(), centre, 2.0 * Frames::kRadius, options, &f.background);
    samples.AddMoving(picture.View(), f.background, balls, 4.0 * Frames::kRadius, options);
  }
  LearnedColour learnt;
  std::string why;
  ASSERT_TRUE(samples.Learn(options, &learnt, &why)) << why;
  EXPECT_EQ(learnt.moving_taken_before, 0.0);
  EXPECT_EQ(learnt.ball_lost, 0.0);
}

// What a learnt colour says: the named balls are what they are named; a dark grey (a shadow or a
// shoe a webcam's learner once followed) is no ball.
TEST(ColourLearning, AWhiteBallIsABrightGrey) {
  EXPECT_TRUE(BallColour::White().IsWhite());
  EXPECT_FALSE(BallColour::Orange().IsGrey());
  EXPECT_FALSE(BallColour::Yellow().IsGrey());
  BallColour dark;
  dark.lit = {65.0f, 118.0f, 141.0f};
  EXPECT_TRUE(dark.IsGrey());
  EXPECT_FALSE(dark.IsWhite());
  BallColour tinted;  // a white ball under a warm light
  tinted.lit = {200.0f, 115.0f, 140.0f};
  EXPECT_TRUE(tinted.IsWhite());
}

TEST(ColourLearning, OptionsAreValidated) {
  ColourLearningOptions options;
  EXPECT_TRUE(options.IsValid(nullptr));
  options.max_ball_loss = 1.0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("ball loss"), std::string::npos);
  options = {};
  options.moving_stride = 0;
  EXPECT_FALSE(options.IsValid(nullptr));
}

}  // namespace
}  // namespace p4::segment
