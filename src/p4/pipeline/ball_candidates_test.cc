// The ball the sync looks for, from a classes file or the hint.
#include "p4/pipeline/ball_candidates.h"

#include <gtest/gtest.h>

#include <cmath>

#include "p4/segment/colour_learning.h"

namespace p4 {
namespace {

// A run that learnt a yellow ball saved its lit colour beside the classes: the sync's faint
// streaks look for that colour, not the hint's orange (--ball auto).
TEST(SyncBallOf, AClassesFilesLitColourIsTheStreaksColour) {
  ColorClassFile file;
  file.classes = segment::DefaultYellowBall();
  file.ball = segment::BallColour::Yellow();
  const SyncBall learnt = SyncBallOf(file, "auto");
  EXPECT_EQ(learnt.classes.classes.size(), file.classes.classes.size());
  EXPECT_FLOAT_EQ(learnt.streak.lit.v, segment::BallColour::Yellow().lit.v);
  EXPECT_GT(std::abs(learnt.streak.lit.v - segment::BallColour::Orange().lit.v), 20.0f);
  // A file without ball_lit: the hint's streaks (orange for auto), the file's classes.
  file.ball.reset();
  EXPECT_FLOAT_EQ(SyncBallOf(file, "auto").streak.lit.v, segment::BallColour::Orange().lit.v);
  EXPECT_FLOAT_EQ(SyncBallOf(file, "white").streak.lit.u, segment::BallColour::White().lit.u);
  // No file: any colour for auto, the named colour's classes otherwise.
  EXPECT_EQ(SyncBallOf(std::nullopt, "auto").classes.classes.size(),
            segment::AnyColour().classes.size());
  EXPECT_EQ(SyncBallOf(std::nullopt, "yellow").classes.classes.size(),
            segment::DefaultYellowBall().classes.size());
}

}  // namespace
}  // namespace p4
