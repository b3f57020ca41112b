#include "p4/eval/evaluate_events.h"

#include <algorithm>
#include <cmath>

#include "p4/eval/json_round.h"

namespace p4 {
namespace {

std::vector<const game::Event*> OfTypes(const std::vector<game::Event>& events,
                                        std::initializer_list<const char*> types) {
  std::vector<const game::Event*> out;
  for (const auto& e : events) {
    for (const char* type : types) {
      if (e.type == type) out.push_back(&e);
    }
  }
  return out;
}

// One-to-one matches, nearest in time first: pairs (truth index, run index).
std::vector<std::pair<int, int>> MatchByTime(const std::vector<const game::Event*>& truth,
                                             const std::vector<const game::Event*>& run,
                                             double window) {
  struct Candidate {
    double dt;
    int i, j;
  };
  std::vector<Candidate> candidates;
  for (int i = 0; i < static_cast<int>(truth.size()); ++i) {
    for (int j = 0; j < static_cast<int>(run.size()); ++j) {
      const double dt = std::abs(truth[i]->t - run[j]->t);
      if (dt <= window) candidates.push_back({dt, i, j});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.dt < b.dt; });
  std::vector<char> ti(truth.size(), 0), rj(run.size(), 0);
  std::vector<std::pair<int, int>> pairs;
  for (const Candidate& c : candidates) {
    if (ti[c.i] || rj[c.j]) continue;
    ti[c.i] = rj[c.j] = 1;
    pairs.emplace_back(c.i, c.j);
  }
  return pairs;
}

double Recall(const std::vector<game::Event>& truth, const std::vector<game::Event>& run,
              std::initializer_list<const char*> truth_types, const char* run_type, double window,
              int* count) {
  const auto t = OfTypes(truth, truth_types);
  *count = static_cast<int>(t.size());
  if (t.empty()) return 1.0;
  return static_cast<double>(MatchByTime(t, OfTypes(run, {run_type}), window).size()) / t.size();
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

nlohmann::ordered_json EventReport::ToJson() const {
  nlohmann::ordered_json j;
  j["bounce_precision"] = RoundTo(bounce_precision, 1e-5);
  j["bounce_recall"] = RoundTo(bounce_recall, 1e-5);
  j["bounces_truth"] = truth_bounces;
  j["bounces_run"] = run_bounces;
  j["bounce_position_median_mm"] = RoundTo(bounce_position_median_mm, 0.001);
  j["bounce_position_max_mm"] = RoundTo(bounce_position_max_mm, 0.001);
  j["bounce_time_median_ms"] = RoundTo(bounce_time_median_ms, 0.001);
  j["bounce_time_max_ms"] = RoundTo(bounce_time_max_ms, 0.001);
  j["net_recall"] = RoundTo(net_recall, 1e-5);
  j["hit_recall"] = RoundTo(hit_recall, 1e-5);
  j["out_recall"] = RoundTo(out_recall, 1e-5);
  j["points_truth"] = truth_points;
  j["points_run"] = run_points;
  j["point_winner_share"] = RoundTo(point_winner_share, 1e-5);
  j["final_score_right"] = final_score_right;
  j["final_score_truth"] = {{"games", truth_games}, {"points", truth_score}};
  j["final_score_run"] = {{"games", run_games}, {"points", run_score}};
  return j;
}

EventReport EvaluateEvents(const std::vector<game::Event>& truth_events,
                           const std::vector<game::Event>& run_events,
                           const EventEvalOptions& options) {
  EventReport r;
  const auto truth_bounces = OfTypes(truth_events, {"bounce"});
  const auto run_bounces = OfTypes(run_events, {"bounce"});
  r.truth_bounces = static_cast<int>(truth_bounces.size());
  r.run_bounces = static_cast<int>(run_bounces.size());
  const auto pairs = MatchByTime(truth_bounces, run_bounces, options.bounce_window_s);
  r.matched_bounces = static_cast<int>(pairs.size());
  r.bounce_recall = r.truth_bounces ? static_cast<double>(pairs.size()) / r.truth_bounces : 1.0;
  r.bounce_precision = r.run_bounces ? static_cast<double>(pairs.size()) / r.run_bounces : 1.0;
  std::vector<double> position_mm, time_ms;
  for (const auto& [i, j] : pairs) {
    time_ms.push_back(1000.0 * std::abs(truth_bounces[i]->t - run_bounces[j]->t));
    if (truth_bounces[i]->position && run_bounces[j]->position) {
      position_mm.push_back(
          1000.0 *
          (truth_bounces[i]->position->head<2>() - run_bounces[j]->position->head<2>()).norm());
    }
  }
  r.bounce_position_median_mm = Median(position_mm);
  r.bounce_position_max_mm =
      position_mm.empty() ? 0.0 : *std::max_element(position_mm.begin(), position_mm.end());
  r.bounce_time_median_ms = Median(time_ms);
  r.bounce_time_max_ms = time_ms.empty() ? 0.0 : *std::max_element(time_ms.begin(), time_ms.end());
  const double w = options.event_window_s;
  r.net_recall = Recall(truth_events, run_events, {"net"}, "net", w, &r.truth_nets);
  r.hit_recall = Recall(truth_events, run_events, {"hit", "serve"}, "hit", w, &r.truth_hits);
  r.out_recall = Recall(truth_events, run_events, {"out"}, "out", w, &r.truth_outs);
  const auto truth_points = OfTypes(truth_events, {"point"});
  const auto run_points = OfTypes(run_events, {"point"});
  r.truth_points = static_cast<int>(truth_points.size());
  r.run_points = static_cast<int>(run_points.size());
  for (const auto& [i, j] : MatchByTime(truth_points, run_points, options.point_window_s)) {
    r.points_winner_right += truth_points[i]->winner == run_points[j]->winner;
  }
  r.point_winner_share =
      r.truth_points ? static_cast<double>(r.points_winner_right) / r.truth_points : 1.0;
  if (!truth_points.empty()) {
    r.truth_games = truth_points.back()->games;
    r.truth_score = truth_points.back()->score;
  }
  if (!run_points.empty()) {
    r.run_games = run_points.back()->games;
    r.run_score = run_points.back()->score;
  }
  r.final_score_right = r.truth_points == r.run_points && r.truth_games == r.run_games &&
                        r.truth_score == r.run_score;
  return r;
}

}  // namespace p4
