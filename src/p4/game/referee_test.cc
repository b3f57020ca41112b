#include "p4/game/referee.h"

#include <gtest/gtest.h>

namespace p4::game {
namespace {

// Events as the detector gives them. Strokes are made behind the player's end unless `at_x`.
Event Hit(double t, char player, double at_x = 0.0) {
  Event e;
  e.t = t;
  e.type = "hit";
  e.player = player;
  const double x = at_x != 0.0 ? at_x : (player == 'A' ? -1.6 : 1.6);
  e.position = Eigen::Vector3d(x, 0.1, 0.25);
  return e;
}
Event Bounce(double t, char side) {
  Event e;
  e.t = t;
  e.type = "bounce";
  e.side = side;
  e.position = Eigen::Vector3d(side == 'A' ? -0.6 : 0.6, 0.0, 0.0);
  return e;
}
Event Plain(double t, const std::string& type) {
  Event e;
  e.t = t;
  e.type = type;
  e.position = Eigen::Vector3d(0.0, 0.2, 0.1);
  return e;
}

class RefereeTest : public ::testing::Test {
 protected:
  // Feeds events (and the clock at each), returns everything the referee published.
  std::vector<Event> Feed(const std::vector<Event>& events) {
    std::vector<Event> out;
    for (const Event& e : events) {
      for (auto& r : referee_.OnTime(e.t, true)) out.push_back(r);
      for (auto& r : referee_.OnEvent(e)) out.push_back(r);
    }
    return out;
  }
  // The ball out of play for a moment: the referee waits for the next serve.
  void Pause() {
    clock_ += 0.5;
    referee_.OnTime(clock_, false);
    clock_ += 0.5;
    referee_.OnTime(clock_, false);
  }
  // One point won by `winner`: a good serve the receiver does not return, or a serve fault.
  std::vector<Event> PlayPoint(char winner) {
    const char server = referee_.score().Server();
    const double t = clock_ += 1.0;
    std::vector<Event> out;
    if (winner == server) {
      out = Feed({Hit(t, server), Bounce(t + 0.2, server),
                  Bounce(t + 0.5, winner == 'A' ? 'B' : 'A'), Plain(t + 0.8, "floor")});
    } else {
      out = Feed({Hit(t, server), Bounce(t + 0.4, winner)});  // straight onto the receiver's half
    }
    clock_ += 1.0;
    Pause();
    return out;
  }
  static const Event* Find(const std::vector<Event>& events, const std::string& type) {
    for (const Event& e : events) {
      if (e.type == type) return &e;
    }
    return nullptr;
  }
  Referee referee_;
  double clock_ = 0.0;
};

TEST_F(RefereeTest, AGoodServeAndARallyEndingInADoubleBounce) {
  const auto out = Feed({Hit(1.0, 'A'), Bounce(1.2, 'A'), Bounce(1.5, 'B'), Hit(1.7, 'B'),
                         Bounce(2.0, 'A'), Hit(2.2, 'A'), Bounce(2.5, 'B'), Bounce(2.8, 'B')});
  ASSERT_NE(Find(out, "serve"), nullptr);
  EXPECT_EQ(Find(out, "serve")->player, 'A');
  const Event* point = Find(out, "point");
  ASSERT_NE(point, nullptr);
  EXPECT_EQ(point->winner, 'A');
  EXPECT_EQ(point->reason, "double bounce");
  EXPECT_DOUBLE_EQ(point->t, 2.8);
  EXPECT_EQ(point->score, (std::array<int, 2>{1, 0}));
}

TEST_F(RefereeTest, ServeFaults) {
  // Straight onto the receiver's half.
  auto out = Feed({Hit(1.0, 'A'), Bounce(1.3, 'B')});
  EXPECT_EQ(Find(out, "point")->winner, 'B');
  EXPECT_EQ(Find(out, "point")->reason, "serve fault");
  clock_ = 2.0;
  Pause();
  // Twice on the server's half (A serves the 2nd point too).
  out = Feed({Hit(4.0, 'A'), Bounce(4.2, 'A'), Bounce(4.5, 'A')});
  EXPECT_EQ(Find(out, "point")->winner, 'B');
  clock_ = 5.0;
  Pause();
  // B serves now: over the end without touching the receiver's half.
  out = Feed({Hit(7.0, 'B'), Bounce(7.2, 'B'), Plain(7.6, "out")});
  EXPECT_EQ(Find(out, "point")->winner, 'A');
  EXPECT_EQ(Find(out, "point")->reason, "serve fault");
  clock_ = 8.0;
  Pause();
  // Into the net and down on the server's half.
  out = Feed({Hit(10.0, 'B'), Bounce(10.2, 'B'), Plain(10.3, "net"), Bounce(10.5, 'B')});
  EXPECT_EQ(Find(out, "point")->winner, 'A');
  EXPECT_EQ(referee_.score().points(), (std::array<int, 2>{2, 2}));
}

TEST_F(RefereeTest, AServeTouchingTheNetAndOtherwiseGoodIsALet) {
  auto out = Feed({Hit(1.0, 'A'), Bounce(1.2, 'A'), Plain(1.35, "net"), Bounce(1.5, 'B')});
  ASSERT_NE(Find(out, "let"), nullptr);
  EXPECT_EQ(Find(out, "point"), nullptr);
  EXPECT_EQ(referee_.points_played(), 0);
  clock_ = 2.0;
  Pause();
  // Replayed by the same server; a rally's net touch is no let: play goes on.
  out = Feed({Hit(4.0, 'A'), Bounce(4.2, 'A'), Bounce(4.5, 'B'), Hit(4.7, 'B'), Plain(4.85, "net"),
              Bounce(5.0, 'A'), Plain(5.4, "floor")});
  EXPECT_EQ(Find(out, "serve")->player, 'A');
  EXPECT_EQ(Find(out, "let"), nullptr);
  EXPECT_EQ(Find(out, "point")->winner, 'B');
  EXPECT_EQ(Find(out, "point")->reason, "no return");
}

TEST_F(RefereeTest, TheBallIntoTheNetOutAndVolleys) {
  // A's return hits the net and drops on A's half.
  auto out = Feed({Hit(1.0, 'A'), Bounce(1.2, 'A'), Bounce(1.5, 'B'), Hit(1.7, 'B'),
                   Bounce(2.0, 'A'), Hit(2.2, 'A'), Plain(2.4, "net"), Bounce(2.5, 'A')});
  EXPECT_EQ(Find(out, "point")->winner, 'B');
  EXPECT_EQ(Find(out, "point")->reason, "net");
  clock_ = 3.0;
  Pause();
  // B's return goes out.
  out = Feed({Hit(5.0, 'A'), Bounce(5.2, 'A'), Bounce(5.5, 'B'), Hit(5.7, 'B'), Plain(6.0, "out"),
              Plain(6.3, "floor")});
  EXPECT_EQ(Find(out, "point")->winner, 'A');
  EXPECT_EQ(Find(out, "point")->reason, "out");
  clock_ = 7.0;
  Pause();
  // B serves; A strikes B's return over the table before it bounced: volley, A loses.
  out = Feed({Hit(9.0, 'B'), Bounce(9.2, 'B'), Bounce(9.5, 'A'), Hit(9.7, 'A'), Bounce(9.9, 'B'),
              Hit(10.0, 'B'), Hit(10.2, 'A', -0.5)});
  EXPECT_EQ(Find(out, "point")->winner, 'B');
  EXPECT_EQ(Find(out, "point")->reason, "volley");
  clock_ = 11.0;
  Pause();
  // Behind the end line the ball was out already: the striker of the long ball loses.
  out = Feed(
      {Hit(13.0, 'B'), Bounce(13.2, 'B'), Bounce(13.5, 'A'), Hit(13.7, 'A'), Hit(14.1, 'B', 2.0)});
  EXPECT_EQ(Find(out, "point")->winner, 'B');
  EXPECT_EQ(Find(out, "point")->reason, "out");
}

TEST_F(RefereeTest, ALostBallEndsTheRallyAgainstWhoeverHadToPlayIt) {
  Feed({Hit(1.0, 'A'), Bounce(1.2, 'A'), Bounce(1.5, 'B')});
  EXPECT_EQ(referee_.to_play(), 'B');
  EXPECT_TRUE(referee_.OnTime(2.0, false).empty());
  const auto out = referee_.OnTime(2.6, false);
  ASSERT_NE(Find(out, "point"), nullptr);
  EXPECT_EQ(Find(out, "point")->winner, 'A');
  EXPECT_EQ(Find(out, "point")->reason, "no return");
  EXPECT_DOUBLE_EQ(Find(out, "point")->t, 1.5);
}

TEST_F(RefereeTest, NothingCountsAfterThePointUntilTheNextServe) {
  auto out = Feed({Hit(1.0, 'A'), Bounce(1.3, 'B')});  // serve fault: B's point
  ASSERT_NE(Find(out, "point"), nullptr);
  // B hits the ball back to A, it bounces twice: the point is over, nothing scores.
  out = Feed({Hit(1.6, 'B'), Bounce(1.9, 'A'), Bounce(2.2, 'A'), Plain(2.5, "floor")});
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(referee_.points_played(), 1);
  // Still in play for the eye (the ball was seen), then gone: the next serve is A's.
  referee_.OnTime(3.0, false);
  referee_.OnTime(3.4, false);
  out = Feed({Hit(4.0, 'B')});  // the receiver's practice stroke is no serve
  EXPECT_TRUE(out.empty());
  out = Feed({Hit(4.5, 'A')});
  ASSERT_NE(Find(out, "serve"), nullptr);
}

TEST_F(RefereeTest, AMissedStrokeDoesNotLoseTheRally) {
  // B's stroke is not seen; its ball lands on A's half: play goes on with A to return.
  const auto out =
      Feed({Hit(1.0, 'A'), Bounce(1.2, 'A'), Bounce(1.5, 'B'), Bounce(2.0, 'A'), Hit(2.2, 'A')});
  EXPECT_EQ(Find(out, "point"), nullptr);
  EXPECT_EQ(referee_.to_play(), 'B');
}

TEST_F(RefereeTest, ServiceOrderDeuceGamesAndTheMatch) {
  referee_ = Referee(RefereeOptions{3, 'A'});
  // Service changes every 2 points: A A B B A A ...
  std::string servers;
  for (int i = 0; i < 6; ++i) {
    servers += referee_.score().Server();
    PlayPoint(i % 2 ? 'A' : 'B');
  }
  EXPECT_EQ(servers, "AABBAA");
  // To 10-10, then service alternates every point and the game needs two clear points.
  while (referee_.score().points()[0] < 10) PlayPoint('A');
  while (referee_.score().points()[1] < 10) PlayPoint('B');
  EXPECT_EQ(referee_.score().points(), (std::array<int, 2>{10, 10}));
  const char s1 = referee_.score().Server();
  PlayPoint('A');  // 11-10: not over
  EXPECT_NE(referee_.score().Server(), s1);
  EXPECT_EQ(referee_.score().games(), (std::array<int, 2>{0, 0}));
  PlayPoint('B');             // 11-11
  PlayPoint('A');             // 12-11
  auto out = PlayPoint('A');  // 13-11: A wins the game
  ASSERT_NE(Find(out, "game"), nullptr);
  EXPECT_EQ(Find(out, "game")->winner, 'A');
  EXPECT_EQ(referee_.score().games(), (std::array<int, 2>{1, 0}));
  // The first server alternates between games: B serves first in game 2.
  EXPECT_EQ(referee_.score().Server(), 'B');
  for (int i = 0; i < 10; ++i) PlayPoint('A');
  out = PlayPoint('A');  // 11-0: 2-0 in games, best of 3
  ASSERT_NE(Find(out, "match"), nullptr);
  EXPECT_EQ(Find(out, "match")->winner, 'A');
  EXPECT_TRUE(referee_.score().match_over());
  // After the match nothing scores.
  EXPECT_TRUE(PlayPoint('B').empty());
}

TEST(RefereeOptions, Validation) {
  std::string error;
  EXPECT_TRUE(RefereeOptions{}.IsValid(&error));
  RefereeOptions even;
  even.best_of = 4;
  EXPECT_FALSE(even.IsValid(&error));
  RefereeOptions bad;
  bad.lost_ball_s = 0.0;
  EXPECT_FALSE(bad.IsValid(&error));
}

}  // namespace
}  // namespace p4::game
