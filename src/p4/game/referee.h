// The referee (paper §4, "monitors the score"): a state machine over the events of play that
// applies the laws of table tennis for singles (ITTF 2.6-2.10) and keeps the score with
// MatchScore. The serve must bounce first on the server's half, then on the receiver's; a serve
// that touches the net and is otherwise good is a let; in a rally the ball must bounce once on
// the opponent's half. A player loses the point for a serve fault, a ball into the net, out, a
// second bounce on their half, failing to return, or striking the ball over the table before it
// bounced on their half (volley, "obstruction"). After a point everything is ignored until the
// next serve (a ball hit back after the point does not score twice).
//
// Pure: events and the clock come in as arguments. Players are 'A' (x < 0) and 'B' (x > 0).
#pragma once

#include <string>
#include <vector>

#include "p4/game/event.h"
#include "p4/game/match_score.h"

namespace p4::game {

struct RefereeOptions {
  int best_of = 5;
  char first_server = 'A';
  // A rally whose ball is not seen for this long ends: whoever had to play it next failed.
  double lost_ball_s = 1.0;
  // After a point, the next serve is awaited once the ball has been out of sight this long (or
  // `max_pause_s` has passed).
  double min_pause_s = 0.25;
  double max_pause_s = 2.0;

  bool IsValid(std::string* error) const;
};

class Referee {
 public:
  explicit Referee(const RefereeOptions& options = {});

  // One detected event (bounce, net, hit, out, floor), in time order. Returns what the referee
  // publishes because of it: serve, let, point, game, match (point: winner, reason, score).
  std::vector<Event> OnEvent(const Event& event);
  // The clock: call once per frame set with whether the ball is tracked; ends a rally whose ball
  // is lost and opens the wait for the next serve.
  std::vector<Event> OnTime(double t, bool ball_seen);

  const MatchScore& score() const { return score_; }
  int points_played() const { return points_played_; }
  // The player who must play the ball next, or 0 when no rally is on.
  char to_play() const;

 private:
  enum class State {
    kWaitingForServe,  // next: the server strikes
    kServed,           // serve struck: first bounce on the server's half expected
    kServeCrossing,    // bounced on the server's half: the receiver's half next
    kInFlight,         // a return struck by hitter_: the opponent's half next
    kToReturn,         // bounced on the opponent's half: they must strike it
    kPointOver,        // decided: waiting for the ball to go out of play
    kMatchOver,
  };
  std::vector<Event> Award(double t, char winner, const std::string& reason);
  std::vector<Event> Let(double t);
  std::vector<Event> Serve(const Event& hit);

  RefereeOptions options_;
  MatchScore score_;
  State state_ = State::kWaitingForServe;
  char hitter_ = 0;   // who struck the ball last
  bool net_ = false;  // the ball touched the net since the last stroke
  double last_seen_ = -1e9, decided_at_ = -1e9;
  int points_played_ = 0;
};

}  // namespace p4::game
