// The game layer of a run against the simulator's truth (`p4track eval`): events matched by type
// and time, point winners matched by time, the final score. Pure.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <vector>

#include "p4/game/event.h"

namespace p4 {

struct EventEvalOptions {
  double bounce_window_s = 0.02;  // a detected bounce within this of a true one matches it
  double event_window_s = 0.05;   // net, hit, out
  double point_window_s = 2.0;    // a point decided within this of the true one matches it
};

struct EventReport {
  int truth_bounces = 0, run_bounces = 0, matched_bounces = 0;
  double bounce_precision = 0.0, bounce_recall = 0.0;
  double bounce_position_median_mm = 0.0, bounce_position_max_mm = 0.0;  // in the table's plane
  double bounce_time_median_ms = 0.0, bounce_time_max_ms = 0.0;
  double net_recall = 0.0, hit_recall = 0.0, out_recall = 0.0;  // truth serves count as hits
  int truth_nets = 0, truth_hits = 0, truth_outs = 0;
  int truth_points = 0, run_points = 0, points_winner_right = 0;
  double point_winner_share = 0.0;  // of the true points
  bool final_score_right = false;
  std::array<int, 2> truth_games{}, truth_score{}, run_games{}, run_score{};

  nlohmann::ordered_json ToJson() const;
};

// `truth_events` and `run_events` as in events.jsonl (the referee's point events carry the
// running score: the last one of each gives the final score).
EventReport EvaluateEvents(const std::vector<game::Event>& truth_events,
                           const std::vector<game::Event>& run_events,
                           const EventEvalOptions& options = {});

}  // namespace p4
