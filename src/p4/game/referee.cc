#include "p4/game/referee.h"

#include "p4/core/table.h"

namespace p4::game {

bool RefereeOptions::IsValid(std::string* error) const {
  if (!MatchScore::IsValid(best_of, first_server, error)) return false;
  if (!(lost_ball_s > 0.0) || !(min_pause_s >= 0.0) || !(max_pause_s >= min_pause_s)) {
    *error = "referee: lost_ball_s must be positive and 0 <= min_pause_s <= max_pause_s";
    return false;
  }
  return true;
}

Referee::Referee(const RefereeOptions& options)
    : options_(options), score_(options.best_of, options.first_server) {}

char Referee::to_play() const {
  switch (state_) {
    case State::kServed:
    case State::kServeCrossing:
    case State::kInFlight:
    case State::kToReturn:
      return MatchScore::Other(hitter_);
    default:
      return 0;
  }
}

std::vector<Event> Referee::Award(double t, char winner, const std::string& reason) {
  const PointOutcome outcome = score_.AwardPoint(winner);
  ++points_played_;
  state_ = outcome.match_over ? State::kMatchOver : State::kPointOver;
  decided_at_ = t;
  return PointEvents(t, winner, reason, outcome);
}

std::vector<Event> Referee::Let(double t) {
  Event let;
  let.t = t;
  let.type = "let";
  state_ = State::kPointOver;  // replayed: the same server serves again
  decided_at_ = t;
  return {let};
}

std::vector<Event> Referee::Serve(const Event& hit) {
  Event serve = hit;
  serve.type = "serve";
  state_ = State::kServed;
  hitter_ = hit.player;
  net_ = false;
  return {serve};
}

std::vector<Event> Referee::OnEvent(const Event& e) {
  if (state_ == State::kMatchOver) return {};
  if (state_ == State::kPointOver) return {};
  const char server = score_.Server();
  const char receiver = score_.Receiver();
  const bool over_table = e.position && std::abs(e.position->x()) < table::kHalfLength &&
                          std::abs(e.position->y()) < table::kHalfWidth;
  switch (state_) {
    case State::kWaitingForServe:
      if (e.type == "hit" && e.player == server) return Serve(e);
      return {};  // practice strokes, the receiver handing the ball back, ...
    case State::kServed:
      if (e.type == "hit" && e.player == server) return Serve(e);  // the real strike after a toss
      if (e.type == "net") net_ = true;
      if (e.type == "bounce") {
        if (e.side == server) {
          state_ = State::kServeCrossing;
          return {};
        }
        return Award(e.t, receiver, "serve fault");  // not on the server's half first
      }
      if (e.type == "out" || e.type == "floor") return Award(e.t, receiver, "serve fault");
      if (e.type == "hit" && e.player == receiver) {
        return Award(e.t, over_table ? server : receiver, over_table ? "volley" : "serve fault");
      }
      return {};
    case State::kServeCrossing:
      if (e.type == "net") net_ = true;
      if (e.type == "bounce") {
        if (e.side == receiver) {
          if (net_) return Let(e.t);
          state_ = State::kToReturn;
          return {};
        }
        return Award(e.t, receiver, "serve fault");  // twice on the server's half
      }
      if (e.type == "out" || e.type == "floor") {
        return Award(e.t, receiver, net_ ? "net" : "serve fault");
      }
      if (e.type == "hit" && e.player == receiver) {
        return Award(e.t, over_table ? server : receiver, over_table ? "volley" : "serve fault");
      }
      return {};
    case State::kInFlight: {
      const char opponent = MatchScore::Other(hitter_);
      if (e.type == "net") net_ = true;
      if (e.type == "bounce") {
        if (e.side == opponent) {
          state_ = State::kToReturn;
          return {};
        }
        return Award(e.t, opponent, net_ ? "net" : "own side");
      }
      if (e.type == "out") return Award(e.t, opponent, "out");
      if (e.type == "floor") return Award(e.t, opponent, net_ ? "net" : "out");
      if (e.type == "hit" && e.player == opponent) {
        // Struck before it bounced: over the table that is a volley (obstruction); beyond the
        // end line the ball was already out.
        return Award(e.t, over_table ? hitter_ : opponent, over_table ? "volley" : "out");
      }
      return {};
    }
    case State::kToReturn: {
      const char player = MatchScore::Other(hitter_);  // the one who must strike it
      if (e.type == "hit" && e.player == player) {
        hitter_ = player;
        net_ = false;
        state_ = State::kInFlight;
        return {};
      }
      if (e.type == "bounce") {
        if (e.side == player) return Award(e.t, hitter_, "double bounce");
        // On the other half without a stroke seen: the stroke was missed; its ball landed well.
        hitter_ = player;
        net_ = false;
        return {};
      }
      if (e.type == "out" || e.type == "floor") return Award(e.t, hitter_, "no return");
      return {};
    }
    default:
      return {};
  }
}

std::vector<Event> Referee::OnTime(double t, bool ball_seen) {
  if (ball_seen) last_seen_ = t;
  switch (state_) {
    case State::kPointOver:
      if ((!ball_seen && t - last_seen_ >= options_.min_pause_s) ||
          t - decided_at_ >= options_.max_pause_s) {
        state_ = State::kWaitingForServe;
      }
      return {};
    case State::kServed:
    case State::kServeCrossing:
      if (t - last_seen_ >= options_.lost_ball_s) {
        return Award(last_seen_, score_.Receiver(), "serve fault");
      }
      return {};
    case State::kInFlight:
      if (t - last_seen_ >= options_.lost_ball_s) {
        return Award(last_seen_, MatchScore::Other(hitter_), net_ ? "net" : "out");
      }
      return {};
    case State::kToReturn:
      if (t - last_seen_ >= options_.lost_ball_s) return Award(last_seen_, hitter_, "no return");
      return {};
    default:
      return {};
  }
}

}  // namespace p4::game
