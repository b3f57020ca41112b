// The counting part of the laws of table tennis for singles (ITTF 2.10-2.13): a game is won by
// the first player to 11 points with a lead of 2; service changes after every 2 points, and after
// every point from 10-10; the player who served first in a game receives first in the next; a
// match is best of N games (N odd). Players are 'A' and 'B'. Pure: no I/O, no clock.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "p4/game/event.h"

namespace p4::game {

struct PointOutcome {
  std::array<int, 2> score{};  // points of A and B after this point (the final score of a game
                               // that this point ended)
  std::array<int, 2> games{};  // games won by A and B after this point
  bool game_over = false;
  bool match_over = false;
};

class MatchScore {
 public:
  // best_of: odd, >= 1. first_server: 'A' or 'B' (of the first game).
  explicit MatchScore(int best_of = 5, char first_server = 'A');

  static bool IsValid(int best_of, char first_server, std::string* error);

  char Server() const;  // who serves the next point
  char Receiver() const { return Other(Server()); }
  PointOutcome AwardPoint(char winner);

  std::array<int, 2> points() const { return points_; }
  std::array<int, 2> games() const { return games_; }
  const std::vector<std::array<int, 2>>& finished_games() const { return finished_; }
  bool match_over() const { return match_over_; }
  char match_winner() const;  // 'A', 'B', or 0 while the match goes on
  int best_of() const { return best_of_; }

  static char Other(char player) { return player == 'A' ? 'B' : 'A'; }
  static int Index(char player) { return player == 'A' ? 0 : 1; }

 private:
  int best_of_;
  char first_server_;
  std::array<int, 2> points_{};
  std::array<int, 2> games_{};
  std::vector<std::array<int, 2>> finished_;
  bool match_over_ = false;
};

// The events that announce an awarded point (DESIGN.md events.jsonl): "point" (winner, reason,
// running score), then "game" and "match" when the point ended them.
std::vector<Event> PointEvents(double t, char winner, const std::string& reason,
                               const PointOutcome& outcome);

}  // namespace p4::game
