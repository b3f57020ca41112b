#include "p4/eval/evaluate.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "p4/eval/json_round.h"

namespace p4 {

nlohmann::ordered_json EvalReport::ToJson() const {
  nlohmann::ordered_json j;
  j["frames"] = frames;
  j["frames_in_play"] = frames_in_play;
  j["frames_seen"] = frames_seen;
  j["rows"] = rows;
  j["measured_rows"] = measured_rows;
  j["position_rmse_mm"] = RoundTo(position_rmse_mm, 0.001);
  j["position_median_mm"] = RoundTo(position_median_mm, 0.001);
  j["position_p95_mm"] = RoundTo(position_p95_mm, 0.001);
  j["position_rmse_all_mm"] = RoundTo(position_rmse_all_mm, 0.001);
  j["recall"] = RoundTo(recall, 1e-5);
  j["false_positive_rate"] = RoundTo(false_positive_rate, 1e-5);
  return j;
}

namespace {

// The truth row to carry to time `t` from: `nearest`, or its neighbour on t's side of a contact
// between them. A contact shows as a velocity jump beyond gravity's; it happened where the two
// rows' flights come closest (the ball leaves the contact where it arrived).
const TruthRow* SameSide(const std::vector<TruthRow>& truth, const TruthRow* nearest, double t,
                         const EvalOptions& options) {
  if (t == nearest->t) return nearest;
  const std::ptrdiff_t i = nearest - truth.data();
  const std::ptrdiff_t j = t >= nearest->t ? i + 1 : i - 1;
  if (j < 0 || j >= static_cast<std::ptrdiff_t>(truth.size()) || !truth[j].in_play) {
    return nearest;
  }
  const TruthRow& a = truth[std::min(i, j)];
  const TruthRow& b = truth[std::max(i, j)];
  const double dt = b.t - a.t;
  const Eigen::Vector3d g(0.0, 0.0, -options.gravity);
  if (!(dt > 0.0) || (b.velocity - a.velocity - g * dt).norm() <= options.contact_mps) {
    return nearest;
  }
  // a carried forward and b carried back by straight lines meet at the contact's time s:
  // a.p + a.v (s - a.t) = b.p + b.v (s - b.t), in the least-squares sense.
  const Eigen::Vector3d dv = a.velocity - b.velocity;
  const Eigen::Vector3d rhs = b.position - a.position + a.velocity * a.t - b.velocity * b.t;
  const double s = dv.squaredNorm() > 0.0 ? dv.dot(rhs) / dv.squaredNorm() : 0.5 * (a.t + b.t);
  return t < s ? &a : &b;
}

}  // namespace

EvalReport Evaluate(const std::vector<TruthRow>& truth, const std::vector<TrajectoryRow>& run,
                    const Rig& rig, const std::vector<std::vector<float>>& visibility,
                    const EvalOptions& options) {
  EvalReport report;
  report.frames = static_cast<int>(truth.size());
  report.rows = static_cast<int>(run.size());
  if (truth.empty()) return report;
  const double period =
      truth.size() > 1 ? (truth.back().t - truth.front().t) / (truth.size() - 1) : 1.0;
  const auto match = [&](double t) -> const TruthRow* {
    const auto it = std::lower_bound(truth.begin(), truth.end(), t,
                                     [](const TruthRow& r, double value) { return r.t < value; });
    const TruthRow* best = nullptr;
    for (auto c : {it, it == truth.begin() ? it : it - 1}) {
      if (c == truth.end()) continue;
      if (std::abs(c->t - t) <= 0.5 * period &&
          (!best || std::abs(c->t - t) < std::abs(best->t - t)))
        best = &*c;
    }
    return best;
  };
  std::vector<double> measured_errors;
  double sum_all = 0.0;
  int n_all = 0, false_positives = 0;
  std::vector<char> has_measurement(truth.size(), 0);
  for (const TrajectoryRow& row : run) {
    const TruthRow* t = match(row.t);
    const bool ball = t && t->in_play;
    // The truth at the row's own time (cameras out of step put rows between the truth's): the
    // nearest truth row carried ballistically over the gap (< half a period; drag and spin move
    // the ball < 0.5 mm in 8 ms), or the one on the row's side of a contact between them.
    const TruthRow* from = ball ? SameSide(truth, t, row.t, options) : nullptr;
    const double gap = from ? row.t - from->t : 0.0;
    const Eigen::Vector3d truth_at =
        from ? Eigen::Vector3d(from->position + gap * from->velocity +
                               Eigen::Vector3d(0.0, 0.0, -0.5 * options.gravity * gap * gap))
             : Eigen::Vector3d::Zero();
    const double error_mm = ball ? 1000.0 * (row.position - truth_at).norm() : 1e9;
    if (ball) {
      sum_all += error_mm * error_mm;
      ++n_all;
    }
    if (!row.measured) continue;
    ++report.measured_rows;
    if (!ball) {
      ++false_positives;
      continue;
    }
    // Every measured row while the ball is in play counts in the error, near or far.
    measured_errors.push_back(error_mm);
    if (error_mm > options.false_positive_mm) {
      ++false_positives;
      continue;
    }
    has_measurement[t - truth.data()] = 1;
  }
  const int views_needed = std::min(options.min_views, rig.size());
  const auto views = [&](std::size_t i) {
    int count = 0;
    for (int c = 0; c < rig.size(); ++c) {
      count += i < visibility.size() ? visibility[i][c] >= options.min_visible
                                     : rig.cameras[c].Sees(truth[i].position, 2.0);
    }
    return count;
  };
  int recalled = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!truth[i].in_play) continue;
    ++report.frames_in_play;
    if (views(i) < views_needed) continue;
    ++report.frames_seen;
    recalled += has_measurement[i];
  }
  if (!measured_errors.empty()) {
    double sum = 0.0;
    for (double e : measured_errors) sum += e * e;
    report.position_rmse_mm = std::sqrt(sum / measured_errors.size());
    std::sort(measured_errors.begin(), measured_errors.end());
    report.position_median_mm = measured_errors[measured_errors.size() / 2];
    report.position_p95_mm = measured_errors[measured_errors.size() * 95 / 100];
  }
  report.position_rmse_all_mm = n_all ? std::sqrt(sum_all / n_all) : 0.0;
  report.recall = report.frames_seen ? static_cast<double>(recalled) / report.frames_seen : 0.0;
  report.false_positive_rate =
      report.measured_rows ? static_cast<double>(false_positives) / report.measured_rows : 0.0;
  return report;
}

}  // namespace p4
