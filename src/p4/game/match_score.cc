#include "p4/game/match_score.h"

#include <cassert>
#include <cstdlib>

namespace p4::game {

MatchScore::MatchScore(int best_of, char first_server)
    : best_of_(best_of), first_server_(first_server) {
  assert(IsValid(best_of, first_server, nullptr));
}

bool MatchScore::IsValid(int best_of, char first_server, std::string* error) {
  if (best_of < 1 || best_of % 2 == 0) {
    if (error) *error = "best-of must be an odd number >= 1 (got " + std::to_string(best_of) + ")";
    return false;
  }
  if (first_server != 'A' && first_server != 'B') {
    if (error) *error = "first server must be A or B";
    return false;
  }
  return true;
}

char MatchScore::Server() const {
  const int game = games_[0] + games_[1];
  const char game_first = game % 2 == 0 ? first_server_ : Other(first_server_);
  const int played = points_[0] + points_[1];
  const bool first_serves = played < 20 ? (played / 2) % 2 == 0 : played % 2 == 0;
  return first_serves ? game_first : Other(game_first);
}

PointOutcome MatchScore::AwardPoint(char winner) {
  PointOutcome outcome;
  if (match_over_) {
    outcome.score = points_;
    outcome.games = games_;
    outcome.match_over = true;
    return outcome;
  }
  ++points_[Index(winner)];
  outcome.score = points_;
  const int lead = std::abs(points_[0] - points_[1]);
  if ((points_[0] >= 11 || points_[1] >= 11) && lead >= 2) {
    outcome.game_over = true;
    ++games_[Index(winner)];
    finished_.push_back(points_);
    points_ = {0, 0};
    if (games_[Index(winner)] >= best_of_ / 2 + 1) match_over_ = true;
  }
  outcome.games = games_;
  outcome.match_over = match_over_;
  return outcome;
}

char MatchScore::match_winner() const {
  if (!match_over_) return 0;
  return games_[0] > games_[1] ? 'A' : 'B';
}

std::vector<Event> PointEvents(double t, char winner, const std::string& reason,
                               const PointOutcome& outcome) {
  Event point;
  point.t = t;
  point.type = "point";
  point.winner = winner;
  point.reason = reason;
  point.score = outcome.score;
  point.games = outcome.games;
  std::vector<Event> out{point};
  for (const auto& [over, type] :
       {std::pair{outcome.game_over, "game"}, std::pair{outcome.match_over, "match"}}) {
    if (!over) continue;
    Event e = point;
    e.type = type;
    e.reason.clear();
    out.push_back(e);
  }
  return out;
}

}  // namespace p4::game
