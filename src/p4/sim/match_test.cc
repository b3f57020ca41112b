#include "p4/sim/match.h"

#include <gtest/gtest.h>

#include <map>

#include "p4/core/table.h"
#include "p4/sim/shot_solver.h"

namespace p4::sim {
namespace {

TEST(ShotSolver, LandsWhereAimed) {
  const BallParams p;
  BallState start;
  start.position = {-1.8, 0.2, 0.25};
  start.spin = {0.0, 2.0 * M_PI * 80.0, 0.0};
  RallyGoal goal;
  goal.landing = {0.9, -0.4};
  goal.net_z = 0.35;
  const auto v = SolveRallyShot(start, goal, p);
  ASSERT_TRUE(v.has_value());
  BallState s = start;
  s.velocity = *v;
  double t = 0.0;
  ContactEvent e;
  while (t < 2.0 && e.kind == Contact::kNone) {
    e = WorldStep(&s, t, 0.0005, p);
    t += 0.0005;
  }
  ASSERT_EQ(e.kind, Contact::kTable);
  EXPECT_NEAR(e.point.x(), 0.9, 0.005);
  EXPECT_NEAR(e.point.y(), -0.4, 0.005);
}

// An independent reading of the truth: replays the events by the laws of table tennis and
// checks every point's winner, and that the running score follows.
void CheckEventsFollowTheRules(const MatchResult& result) {
  std::array<int, 2> score{0, 0};
  std::array<int, 2> games{0, 0};
  std::vector<const TruthEvent*> rally;
  int points = 0;
  bool dead = false;  // after a point, until the next serve
  for (const TruthEvent& e : result.events) {
    if (e.type == "game" || e.type == "match") continue;
    if (e.type == "serve") dead = false;
    if (dead) continue;
    if (e.type != "point") {
      rally.push_back(&e);
      continue;
    }
    ++points;
    ASSERT_FALSE(rally.empty());
    ASSERT_EQ(rally[0]->type, "serve");
    // Walk the rally: who struck last and which bounces followed.
    char striker = rally[0]->player;
    int own_bounces = 0, opp_bounces = 0;
    bool serve = true, net = false, out = false, floor = false;
    char expected_winner = 0;
    for (std::size_t i = 1; i < rally.size() && !expected_winner; ++i) {
      const TruthEvent& r = *rally[i];
      const char opp = striker == 'A' ? 'B' : 'A';
      if (r.type == "hit") {
        ASSERT_EQ(r.player, opp) << "t=" << r.t;
        // A legal return needs exactly the bounces the rules ask for before it.
        ASSERT_EQ(opp_bounces, 1) << "t=" << r.t;
        ASSERT_EQ(own_bounces, serve ? 1 : 0) << "t=" << r.t;
        ASSERT_FALSE(net);
        striker = r.player;
        own_bounces = opp_bounces = 0;
        serve = false;
      } else if (r.type == "bounce") {
        if (r.side == striker) {
          ++own_bounces;
          if (!serve || own_bounces > 1 || opp_bounces > 0) expected_winner = opp;
        } else {
          ++opp_bounces;
          if (serve && own_bounces == 0) expected_winner = opp;
          if (opp_bounces == 2) expected_winner = striker;
        }
      } else if (r.type == "net") {
        net = true;
      } else if (r.type == "out") {
        out = true;
        if (opp_bounces == 0) expected_winner = opp;
      } else if (r.type == "floor") {
        floor = true;
        expected_winner = opp_bounces == 1 ? striker : opp;
      }
    }
    (void)out;
    (void)floor;
    std::string trace;
    for (const TruthEvent* r : rally)
      trace += " " + r->type + (r->side ? std::string(1, r->side) : "");
    ASSERT_NE(expected_winner, 0) << "no decision in the rally before t=" << e.t << ":" << trace;
    EXPECT_EQ(e.winner, expected_winner) << "point at t=" << e.t << " (" << e.reason << ")";
    ++score[e.winner == 'A' ? 0 : 1];
    EXPECT_EQ(e.score, score) << "t=" << e.t;
    const int lead = std::abs(score[0] - score[1]);
    if ((score[0] >= 11 || score[1] >= 11) && lead >= 2) {
      ++games[e.winner == 'A' ? 0 : 1];
      score = {0, 0};
    }
    EXPECT_EQ(e.games, games);
    rally.clear();
    dead = true;
  }
  EXPECT_EQ(points, result.points_played);
}

TEST(SimulateMatch, EventsFollowTheRulesAndEveryEndingOccurs) {
  MatchOptions options;
  options.points = 40;
  options.seed = 3;
  const MatchResult result = SimulateMatch(options);
  EXPECT_EQ(result.points_played, 40);
  CheckEventsFollowTheRules(result);
  std::map<std::string, int> reasons;
  int serves_by_a = 0;
  for (const TruthEvent& e : result.events) {
    if (e.type == "point") ++reasons[e.reason];
    if (e.type == "serve" && e.player == 'A') ++serves_by_a;
  }
  for (const auto& [reason, count] : reasons) std::printf("%s: %d\n", reason.c_str(), count);
  for (const char* reason : {"serve fault", "net", "out", "no return", "double bounce"}) {
    EXPECT_GT(reasons[reason], 0) << reason;
  }
  EXPECT_EQ(serves_by_a, 20);  // 40 points, service every 2 points, no deuce yet at 40 points
}

TEST(SimulateMatch, ServiceOrderFollowsTheScore) {
  MatchOptions options;
  options.points = 12;
  options.first_server = 'B';
  options.seed = 11;
  const MatchResult result = SimulateMatch(options);
  std::vector<char> servers;
  for (const TruthEvent& e : result.events) {
    if (e.type == "serve") servers.push_back(e.player);
  }
  ASSERT_EQ(servers.size(), 12u);
  for (std::size_t i = 0; i < servers.size(); ++i) {
    EXPECT_EQ(servers[i], (i / 2) % 2 == 0 ? 'B' : 'A') << i;
  }
}

TEST(SimulateMatch, SameSeedSameMatch) {
  MatchOptions options;
  options.points = 5;
  options.seed = 99;
  const MatchResult a = SimulateMatch(options);
  const MatchResult b = SimulateMatch(options);
  ASSERT_EQ(a.trajectory.samples().size(), b.trajectory.samples().size());
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t i = 0; i < a.events.size(); ++i) {
    EXPECT_EQ(a.events[i].t, b.events[i].t);
    EXPECT_EQ(a.events[i].type, b.events[i].type);
  }
  options.seed = 100;
  const MatchResult c = SimulateMatch(options);
  EXPECT_NE(a.events[1].t, c.events[1].t);
}

TEST(SimulateMatch, ShotsHaveRealisticSpeedAndBouncesAreOnTheTable) {
  MatchOptions options;
  options.points = 20;
  options.seed = 5;
  const MatchResult result = SimulateMatch(options);
  int hits = 0;
  for (const TruthEvent& e : result.events) {
    if (e.type == "bounce") {
      EXPECT_TRUE(table::OnSurface(e.position->x(), e.position->y()));
      EXPECT_EQ(e.side, table::SideOf(e.position->x()));
    }
    if (e.type == "hit") {
      const auto after = result.trajectory.At(e.t + 1e-4);
      ASSERT_TRUE(after.has_value());
      EXPECT_LE(after->velocity.norm(), 25.5);
      EXPECT_LE(after->spin.norm(), 2.0 * M_PI * 160.0);
      ++hits;
    }
  }
  EXPECT_GT(hits, 5);
  // The trajectory is continuous in position (no jumps) within segments.
  const auto& samples = result.trajectory.samples();
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].segment != samples[i - 1].segment) continue;
    EXPECT_LT((samples[i].state.position - samples[i - 1].state.position).norm(), 0.02);
  }
}

}  // namespace
}  // namespace p4::sim
