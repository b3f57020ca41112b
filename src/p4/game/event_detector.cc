#include "p4/game/event_detector.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace p4::game {

bool EventDetectorOptions::IsValid(std::string* error) const {
  if (!(break_m > 0.0) || confirm_points < 2 || !(max_gap_s > 0.0) || !(window_s > 0.0) ||
      min_free_fit < 4 || !(ball_radius > 0.0) || !(min_hit_dv > 0.0)) {
    *error =
        "event detector: break_m, max_gap_s, window_s, ball_radius, min_hit_dv must be positive, "
        "confirm_points >= 2, min_free_fit >= 4";
    return false;
  }
  return true;
}

EventDetector::EventDetector(const EventDetectorOptions& options) : options_(options) {}

Eigen::Vector3d EventDetector::Fit::At(double t) const {
  const double s = t - t0;
  return a + s * b + s * s * c;
}

Eigen::Vector3d EventDetector::Fit::VelocityAt(double t) const { return b + 2.0 * (t - t0) * c; }

EventDetector::Fit EventDetector::FitSamples(std::span<const Sample> samples, bool window) const {
  std::size_t first = 0;  // with `window`: the first sample within window_s of the last
  while (window && first + 1 < samples.size() &&
         samples[first].t < samples.back().t - options_.window_s) {
    ++first;
  }
  const std::span<const Sample> use = samples.subspan(first);
  Fit fit;
  fit.t0 = use.back().t;
  const int n = static_cast<int>(use.size());
  fit.samples = n;
  const bool free = n >= options_.min_free_fit;
  const int cols = free ? 3 : 2;
  Eigen::MatrixXd A(n, cols);
  Eigen::MatrixXd rhs(n, 3);
  const Eigen::Vector3d gravity_term(0.0, 0.0, -0.5 * options_.gravity);
  for (int i = 0; i < n; ++i) {
    const double s = use[i].t - fit.t0;
    A(i, 0) = 1.0;
    A(i, 1) = s;
    if (free) A(i, 2) = s * s;
    rhs.row(i) = (free ? use[i].p : Eigen::Vector3d(use[i].p - s * s * gravity_term)).transpose();
  }
  if (n == 1) {
    fit.a = use[0].p;
    fit.b.setZero();
    fit.c = gravity_term;
    return fit;
  }
  const Eigen::MatrixXd x = A.colPivHouseholderQr().solve(rhs);
  fit.a = x.row(0).transpose();
  fit.b = x.row(1).transpose();
  fit.c = free ? Eigen::Vector3d(x.row(2).transpose()) : gravity_term;
  return fit;
}

std::vector<Event> EventDetector::Push(double t, const Eigen::Vector3d& position) {
  std::vector<Event> out;
  const Sample sample{t, position};
  const double last_t = !pending_.empty() ? pending_.back().t
                        : !piece_.empty() ? piece_.back().t
                                          : t;
  if (t - last_t > options_.max_gap_s) out = Flush();  // a long gap ends the piece
  if (piece_.size() < 3) {
    if (!piece_.empty()) CheckCrossings(piece_.back(), sample, &out);
    piece_.push_back(sample);
    return out;
  }
  const Fit fit = FitSamples(piece_, true);
  if ((fit.At(t) - position).norm() <= options_.break_m) {
    pending_.clear();  // what did not fit were stray points
    CheckCrossings(piece_.back(), sample, &out);
    piece_.push_back(sample);
    return out;
  }
  pending_.push_back(sample);
  while (static_cast<int>(pending_.size()) >= options_.confirm_points) {
    const Fit after = FitSamples(pending_, false);
    double worst = 0.0;
    for (const Sample& s : pending_) worst = std::max(worst, (after.At(s.t) - s.p).norm());
    if (worst <= options_.break_m) {
      Cut(&out);
      break;
    }
    pending_.erase(pending_.begin());  // the first of them was a stray point
  }
  return out;
}

std::vector<Event> EventDetector::Flush() {
  std::vector<Event> out;
  if (pending_.size() >= 2 && piece_.size() >= 3) Cut(&out);
  // The ball lost from sight on its way down beside the table (behind a player, below the
  // table's edge in every view): out, if its flight crosses the surface's plane outside the
  // table soon after the last point.
  if (!out_reported_ && piece_.size() >= 3) {
    const Fit fit = FitSamples(piece_, true);
    const double r = options_.ball_radius;
    const Sample& last = piece_.back();
    for (double t = last.t; t <= last.t + options_.max_extrapolation_s; t += 0.001) {
      const Eigen::Vector3d p = fit.At(t);
      if (p.z() >= r) continue;
      if (fit.VelocityAt(t).z() < 0.0 && !table::OnSurface(p.x(), p.y())) {
        Event e;
        e.t = t;
        e.type = "out";
        e.position = Eigen::Vector3d(p.x(), p.y(), 0.0);
        e.confidence = 0.6;
        out.push_back(e);
      }
      break;
    }
  }
  piece_.clear();
  pending_.clear();
  net_reported_ = out_reported_ = false;
  return out;
}

void EventDetector::CheckCrossings(const Sample& from, const Sample& to, std::vector<Event>* out) {
  const double r = options_.ball_radius;
  // Through the net plane below the net's top (with the ball's radius): it touched the net.
  if (!net_reported_ && (from.p.x() < 0.0) != (to.p.x() < 0.0)) {
    const double f = from.p.x() / (from.p.x() - to.p.x());
    const Eigen::Vector3d at = from.p + f * (to.p - from.p);
    // (The detector's margins: 5 mm under the top plus a radius, a radius beyond the posts.)
    if (at.z() > 0.0 && table::MeetsNet(at.y(), at.z(), r, -0.005, r)) {
      Event e;
      e.t = from.t + f * (to.t - from.t);
      e.type = "net";
      e.position = Eigen::Vector3d(0.0, at.y(), std::min(at.z(), table::kNetHeight));
      e.confidence = 0.8;
      out->push_back(e);
      net_reported_ = true;
    }
  }
  // Down through the surface's plane (centre at one radius) outside the table: out.
  if (!out_reported_ && from.p.z() >= r && to.p.z() < r) {
    const double f = (from.p.z() - r) / (from.p.z() - to.p.z());
    const Eigen::Vector3d at = from.p + f * (to.p - from.p);
    if (!table::OnSurface(at.x(), at.y())) {
      Event e;
      e.t = from.t + f * (to.t - from.t);
      e.type = "out";
      e.position = Eigen::Vector3d(at.x(), at.y(), 0.0);
      e.confidence = 0.9;
      out->push_back(e);
      out_reported_ = true;
    }
  }
}

void EventDetector::Cut(std::vector<Event>* out) {
  Fit after = FitSamples(pending_, false);
  // The last points of the piece may belong after the cut (a bounce just before a frame).
  for (int k = 0; k < 2 && piece_.size() > 3; ++k) {
    const Sample last = piece_.back();
    piece_.pop_back();
    const Fit before = FitSamples(piece_, true);
    if ((after.At(last.t) - last.p).norm() < (before.At(last.t) - last.p).norm()) {
      pending_.insert(pending_.begin(), last);
      after = FitSamples(pending_, false);
    } else {
      piece_.push_back(last);
      break;
    }
  }
  const Fit before = FitSamples(piece_, true);
  // Where the two pieces meet: the closest approach of their fits around the gap between them.
  const double ta = piece_.back().t, tb = pending_.front().t;
  const double margin = 0.5 * (tb - ta) + 1e-3;
  double best_t = ta, best_d = 1e9;
  for (int i = 0; i <= 200; ++i) {
    const double t = ta - margin + (tb - ta + 2.0 * margin) * i / 200.0;
    const double d = (before.At(t) - after.At(t)).norm();
    if (d < best_d) best_d = d, best_t = t;
  }
  const Eigen::Vector3d at = 0.5 * (before.At(best_t) + after.At(best_t));
  const Eigen::Vector3d v0 = before.VelocityAt(best_t), v1 = after.VelocityAt(best_t);
  const double confidence =
      std::clamp(std::min(before.samples / 6.0, pending_.size() / 4.0), 0.2, 1.0) *
      std::clamp(1.0 - best_d / (4.0 * options_.break_m), 0.2, 1.0);
  Event e;
  e.t = best_t;
  e.confidence = confidence;
  const bool flips = v0.z() < -options_.bounce_min_vz && v1.z() > options_.bounce_min_vz;
  // A bounce slows the ball along x; a stroke sends it back (or, after a toss, away).
  const bool reverses = (v0.x() < 0.0) != (v1.x() < 0.0) && std::abs(v1.x()) > 1.0;
  const bool struck = reverses || (std::abs(v0.x()) < 0.5 && std::abs(v1.x()) > 1.0);
  const double m = options_.table_margin;
  if (flips && !reverses && at.z() < options_.bounce_max_z && table::OnSurface(at.x(), at.y(), m)) {
    e.type = "bounce";
    e.side = table::SideOf(at.x());
    e.position = Eigen::Vector3d(at.x(), at.y(), 0.0);
  } else if (flips && at.z() < table::kFloorZ + 0.1) {
    e.type = "floor";
    e.position = Eigen::Vector3d(at.x(), at.y(), table::kFloorZ);
  } else if (std::abs(at.x()) < options_.net_reach &&
             at.z() < table::kNetHeight + options_.ball_radius + 0.03 &&
             std::abs(at.y()) < table::kNetHalfLength + 0.05) {
    e.type = "net";
    e.position = Eigen::Vector3d(0.0, at.y(), std::min(at.z(), table::kNetHeight));
  } else if (struck && (v1 - v0).norm() >= options_.min_hit_dv) {
    e.type = "hit";
    e.player = table::SideOf(at.x());
    e.position = at;
  }
  if (!e.type.empty() && !(e.type == "net" && net_reported_)) out->push_back(e);
  if (e.type == "net") net_reported_ = true;
  // The new piece starts after the cut; "out" and "net" are watched afresh after a bounce or hit.
  piece_ = pending_;
  pending_.clear();
  if (e.type == "bounce" || e.type == "hit") net_reported_ = out_reported_ = false;
}

}  // namespace p4::game
