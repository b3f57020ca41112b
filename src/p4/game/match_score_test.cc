#include "p4/game/match_score.h"

#include <gtest/gtest.h>

namespace p4::game {
namespace {

TEST(MatchScore, ServiceChangesEveryTwoPoints) {
  MatchScore score(5, 'A');
  const char expected[] = {'A', 'A', 'B', 'B', 'A', 'A', 'B', 'B'};
  for (char server : expected) {
    EXPECT_EQ(score.Server(), server);
    score.AwardPoint('A');
  }
}

TEST(MatchScore, DeuceChangesServiceEveryPointAndNeedsTwoClear) {
  MatchScore score(5, 'B');
  for (int i = 0; i < 10; ++i) {
    score.AwardPoint('A');
    score.AwardPoint('B');
  }
  EXPECT_EQ(score.points(), (std::array<int, 2>{10, 10}));
  // 20 points played: the first server of the game serves, then every point alternates.
  EXPECT_EQ(score.Server(), 'B');
  EXPECT_FALSE(score.AwardPoint('A').game_over);  // 11-10
  EXPECT_EQ(score.Server(), 'A');
  EXPECT_FALSE(score.AwardPoint('B').game_over);  // 11-11
  EXPECT_EQ(score.Server(), 'B');
  score.AwardPoint('B');                           // 11-12
  const PointOutcome end = score.AwardPoint('B');  // 11-13
  EXPECT_TRUE(end.game_over);
  EXPECT_EQ(end.score, (std::array<int, 2>{11, 13}));
  EXPECT_EQ(end.games, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(score.points(), (std::array<int, 2>{0, 0}));
  // The first server alternates between games.
  EXPECT_EQ(score.Server(), 'A');
}

TEST(MatchScore, BestOfThreeEndsAtTwoGames) {
  MatchScore score(3, 'A');
  PointOutcome last;
  for (int game = 0; game < 2; ++game) {
    for (int i = 0; i < 11; ++i) last = score.AwardPoint('B');
  }
  EXPECT_TRUE(last.match_over);
  EXPECT_EQ(score.match_winner(), 'B');
  EXPECT_EQ(score.finished_games().size(), 2u);
  // Points after the end change nothing.
  const PointOutcome after = score.AwardPoint('A');
  EXPECT_EQ(after.games, (std::array<int, 2>{0, 2}));
}

TEST(MatchScore, ValidatesOptions) {
  std::string error;
  EXPECT_FALSE(MatchScore::IsValid(4, 'A', &error));
  EXPECT_NE(error.find("odd"), std::string::npos);
  EXPECT_FALSE(MatchScore::IsValid(5, 'C', &error));
  EXPECT_TRUE(MatchScore::IsValid(7, 'B', &error));
}

}  // namespace
}  // namespace p4::game
