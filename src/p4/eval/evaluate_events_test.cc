#include "p4/eval/evaluate_events.h"

#include <gtest/gtest.h>

namespace p4 {
namespace {

game::Event E(double t, const std::string& type, double x = 0.0, double y = 0.0) {
  game::Event e;
  e.t = t;
  e.type = type;
  e.position = Eigen::Vector3d(x, y, 0.0);
  return e;
}
game::Event Point(double t, char winner, std::array<int, 2> score) {
  game::Event e;
  e.t = t;
  e.type = "point";
  e.winner = winner;
  e.score = score;
  return e;
}

TEST(EvaluateEvents, MatchesBouncesByTimeAndMeasuresTheirErrors) {
  const std::vector<game::Event> truth{
      E(1.000, "bounce", -0.5, 0.1), E(1.400, "bounce", 0.5, 0.1), E(1.600, "hit"), E(1.610, "net"),
      E(2.000, "bounce", -0.3, 0.0), Point(2.5, 'A', {1, 0})};
  const std::vector<game::Event> run{E(1.002, "bounce", -0.503, 0.104),  // 5 mm, 2 ms
                                     E(1.415, "bounce", 0.5, 0.1),       // 15 ms
                                     E(1.700, "bounce", 0.9, 0.1),       // no true bounce
                                     E(1.605, "hit"), Point(3.1, 'A', {1, 0})};
  const EventReport r = EvaluateEvents(truth, run);
  EXPECT_EQ(r.truth_bounces, 3);
  EXPECT_EQ(r.run_bounces, 3);
  EXPECT_EQ(r.matched_bounces, 2);
  EXPECT_NEAR(r.bounce_recall, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.bounce_precision, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.bounce_position_max_mm, 5.0, 1e-6);
  EXPECT_NEAR(r.bounce_time_max_ms, 15.0, 1e-6);
  EXPECT_DOUBLE_EQ(r.hit_recall, 1.0);
  EXPECT_DOUBLE_EQ(r.net_recall, 0.0);
  EXPECT_DOUBLE_EQ(r.point_winner_share, 1.0);
  EXPECT_TRUE(r.final_score_right);
}

TEST(EvaluateEvents, AWrongWinnerOrAMissingPointIsSeen) {
  const std::vector<game::Event> truth{Point(2.0, 'A', {1, 0}), Point(6.0, 'B', {1, 1})};
  const std::vector<game::Event> wrong{Point(2.2, 'B', {0, 1}), Point(6.1, 'B', {0, 2})};
  EventReport r = EvaluateEvents(truth, wrong);
  EXPECT_DOUBLE_EQ(r.point_winner_share, 0.5);
  EXPECT_FALSE(r.final_score_right);
  const std::vector<game::Event> missing{Point(2.2, 'A', {1, 0})};
  r = EvaluateEvents(truth, missing);
  EXPECT_DOUBLE_EQ(r.point_winner_share, 0.5);
  EXPECT_FALSE(r.final_score_right);
}

}  // namespace
}  // namespace p4
