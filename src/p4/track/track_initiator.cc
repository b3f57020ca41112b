#include "p4/track/track_initiator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "p4/track/flight_model.h"

namespace p4::track {

bool TrackInitiatorOptions::IsValid(std::string* error) const {
  if (!fall.IsValid(error)) return false;
  if (confirm_points < 2 || !(min_travel >= 0.0) || !(min_travel_speed >= 0.0) || !(gate > 0.0) ||
      !(toss_max_lean >= 0.0) || !(gate_sigmas >= 0.0) || !(max_gap_s > 0.0) ||
      !(fall_span_s > 0.0) || !(fall_tolerance > 0.0) || fall_points < 4 ||
      !(fit_tolerance > 0.0) || !(fit_sigmas >= 0.0) || !(max_span_s > max_gap_s) ||
      !(max_speed > 0.0) || max_tracklets < 1 || max_missed < 0 || max_missed_one_view < 0 ||
      min_confirm_points < 2 || min_confirm_points > confirm_points || !(confirm_span_s > 0.0) ||
      !(min_travel_sigmas >= 0.0) || !(fall_max_curvature_sigma > 0.0)) {
    if (error) {
      *error =
          "track initiator: need 2 <= min_confirm_points <= confirm_points, positive gate, gap, "
          "confirming span, speed, tracklets and curvature sigma, travel sigmas >= 0, and a span "
          "longer than the gap";
    }
    return false;
  }
  return true;
}

TrackInitiator::TrackInitiator(const TrackInitiatorOptions& options) : options_(options) {}

namespace {

// The points' noise along three axes (the eigenvectors of the newest point's covariance): per
// axis the largest sigma of any point. Views of two cameras or more are as good in every
// direction (one sigma, any axes); one camera's are known along its ray from the diameter only,
// ~50x worse than across it, and every test below is made per axis.
struct NoiseAxes {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();     // m
};

// Axes of `newest`'s covariance; sigmas from the points given to Widen.
NoiseAxes AxesOf(const Measurement& newest) {
  NoiseAxes n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(newest.covariance);
  if (eigen.info() == Eigen::Success) n.axes = eigen.eigenvectors();
  return n;
}

void Widen(const Measurement& m, NoiseAxes* n) {
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = n->axes.col(i);
    n->sigma(i) = std::max(n->sigma(i), std::sqrt(std::max(0.0, e.dot(m.covariance * e))));
  }
}

NoiseAxes AxesOf(std::span<const TrackletPoint> points) {
  NoiseAxes n = AxesOf(points.back().measurement);
  for (const TrackletPoint& p : points) Widen(p.measurement, &n);
  return n;
}

// Of two points, the axes of `b`'s covariance.
NoiseAxes AxesOf(const TrackletPoint& a, const TrackletPoint& b) {
  NoiseAxes n = AxesOf(b.measurement);
  Widen(a.measurement, &n);
  Widen(b.measurement, &n);
  return n;
}

// |d| in units of `scale` along the columns of `axes`: <= 1 inside the ellipsoid of those
// semi-axes.
double Scaled(const Eigen::Matrix3d& axes, const Eigen::Vector3d& scale, const Eigen::Vector3d& d) {
  return (axes.transpose() * d).cwiseQuotient(scale).norm();
}

// The points' distances from the best flight through them: p0 + v t + a t^2 / 2 with gravity
// and the drag at the mean velocity (first fitted without drag), by least squares; each in units
// of `scale` along the noise axes (one scale for all: the fit is the same).
Eigen::VectorXd FlightResiduals(std::span<const TrackletPoint> points, const NoiseAxes& noise,
                                const Eigen::Vector3d& scale, double gravity,
                                double drag_per_mass) {
  const auto n = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd a(n, 2);
  Eigen::MatrixXd b(n, 3);
  const TimeNs t0 = points.front().t;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = ToSeconds(points[static_cast<std::size_t>(i)].t - t0);
    a.row(i) << 1.0, t;
  }
  const auto qr = a.colPivHouseholderQr();
  Eigen::Vector3d accel(0.0, 0.0, -gravity);
  Eigen::MatrixXd fit;
  for (int pass = 0; pass < 2; ++pass) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = a(i, 1);
      b.row(i) = (points[static_cast<std::size_t>(i)].measurement.position - 0.5 * t * t * accel)
                     .transpose();
    }
    fit = qr.solve(b);  // row 0: p0, row 1: v
    const Eigen::Vector3d v = fit.row(1).transpose();
    accel = Eigen::Vector3d(0.0, 0.0, -gravity) - drag_per_mass * v.norm() * v;
  }
  const Eigen::MatrixXd scaled = (a * fit - b) * noise.axes * scale.cwiseInverse().asDiagonal();
  return scaled.rowwise().norm();
}

// Whether scaled residuals have an RMS within 1.
bool WithinOne(const Eigen::VectorXd& residuals) {
  return residuals.squaredNorm() <= static_cast<double>(residuals.size());
}

}  // namespace

TrackInitiator::Gate TrackInitiator::Predict(const Tracklet& tracklet, TimeNs t) const {
  const TrackletPoint& last = tracklet.points.back();
  const double dt = ToSeconds(t - last.t);
  const Eigen::Vector3d& p1 = last.measurement.position;
  if (tracklet.points.size() == 1) {
    return {p1, Eigen::Matrix3d::Identity(),
            Eigen::Vector3d::Constant(options_.gate + options_.max_speed * dt)};
  }
  const TrackletPoint& before = tracklet.points[tracklet.points.size() - 2];
  const double dt01 = ToSeconds(last.t - before.t);
  // The mean velocity is the one at the middle of the interval: carried to the last point, then
  // the ball flown dt on (the tracker's flight model: gravity and drag, no spin).
  const Eigen::Vector3d no_spin = Eigen::Vector3d::Zero();
  Eigen::Vector3d middle = p1;  // (its position is not needed)
  Eigen::Vector3d v = (p1 - before.measurement.position) / dt01;
  MidpointStep<double>(&middle, &v, no_spin, 0.5 * dt01, options_.gravity, options_.drag_per_mass);
  Eigen::Vector3d predicted = p1;
  MidpointStep<double>(&predicted, &v, no_spin, dt, options_.gravity, options_.drag_per_mass);
  // The velocity is as good as the two points' difference: its error grows with dt / dt01.
  const NoiseAxes noise = AxesOf(before, last);
  const double growth = options_.gate_sigmas * (1.0 + 1.5 * dt / dt01);
  return {predicted, noise.axes, (options_.gate + growth * noise.sigma.array()).matrix()};
}

std::size_t TrackInitiator::FlightStart(const Tracklet& tracklet) const {
  const std::span<const TrackletPoint> points(tracklet.points);
  const std::size_t n = points.size();
  std::size_t first = n - std::min<std::size_t>(n, options_.confirm_points);
  // Each earlier point joins while it lies on the flight itself, not only within the RMS that
  // many points after it dilute.
  while (first > 0) {
    const Eigen::VectorXd residuals = Residuals(points.subspan(first - 1));
    if (residuals(0) > 1.0 || !WithinOne(residuals)) break;
    --first;
  }
  return first;
}

Eigen::VectorXd TrackInitiator::Residuals(std::span<const TrackletPoint> points) const {
  const NoiseAxes noise = AxesOf(points);
  const Eigen::Vector3d scale =
      (options_.fit_tolerance + options_.fit_sigmas * noise.sigma.array()).matrix();
  return FlightResiduals(points, noise, scale, options_.gravity, options_.drag_per_mass);
}

bool TrackInitiator::FitsOneFlight(std::span<const TrackletPoint> points) const {
  return WithinOne(Residuals(points));
}

FallFit TrackInitiator::Fall(std::span<const TrackletPoint> points) const {
  std::vector<FallPoint> window;
  window.reserve(points.size());
  for (const TrackletPoint& p : points) {
    window.push_back({p.t, p.measurement.position, p.measurement.covariance});
  }
  FlightModel model;
  model.gravity = options_.gravity;
  model.drag_per_mass = options_.drag_per_mass;
  return JudgeFall(window, options_.fall, model);
}

bool TrackInitiator::Confirmed(const Tracklet& tracklet, bool at_end) const {
  const auto& points = tracklet.points;
  const int n = static_cast<int>(points.size());
  // Whether `count` of its points are enough to confirm it.
  const auto long_enough = [&](int count) {
    return count >= options_.confirm_points ||
           (at_end && count >= options_.min_confirm_points &&
            std::all_of(points.begin(), points.end(),
                        [](const TrackletPoint& p) { return p.measurement.cameras >= 2; })) ||
           (count >= options_.min_confirm_points &&
            ToSeconds(points.back().t - points.front().t) >= options_.confirm_span_s &&
            std::all_of(points.begin(), points.end(),
                        [](const TrackletPoint& p) { return p.streak; }));
  };
  // Points that do not show the ball's colour (skin or a sleeve brightening the floor) do not
  // count toward confirm_points or min_confirm_points, whichever way the tracklet confirms (they
  // stay in the fits, and in the fall's fall_points).
  const auto off_colour = std::count_if(points.begin(), points.end(),
                                        [](const TrackletPoint& p) { return p.off_colour; });
  if (!long_enough(n - static_cast<int>(off_colour))) return false;
  // One flight through the newest confirm_points: a stray that joined a still spot, or a hand's
  // turn, fits none (older points may lie before a bounce).
  const auto newest =
      std::span<const TrackletPoint>(points).last(std::min(n, options_.confirm_points));
  if (!FitsOneFlight(newest)) return false;
  // Its last fall.window_s must not be judged to fall short of a ball's (a shoe moving level),
  // nor be unjudged when a track that followed it ended for that.
  const FallFit fall = Fall(points);
  if (fall.not_falling || (tracklet.not_ball && !fall.judged)) return false;
  const Eigen::Vector3d travel =
      points.back().measurement.position - points.front().measurement.position;
  const double span = ToSeconds(points.back().t - points.front().t);
  // The travel must also stand out of the two ends' noise (one camera's depth alone wanders by
  // more than min_travel).
  const NoiseAxes end_noise = AxesOf(points.front(), points.back());
  const Eigen::Vector3d travel_sigma =
      (std::sqrt(2.0) * end_noise.sigma.array().max(1e-9)).matrix();
  const bool travelled = Scaled(end_noise.axes, travel_sigma, travel) >= options_.min_travel_sigmas;
  // Its travel says it flies fast: its points whose views stood still in a camera where that says
  // it flies along the ray count for nothing (a still speck paired with a moving one).
  const auto still_and_moving = std::count_if(
      points.begin(), points.end(), [](const TrackletPoint& p) { return p.still_and_moving; });
  if (travelled && travel.norm() >= options_.min_travel &&
      travel.norm() >= options_.min_travel_speed * span &&
      long_enough(n - static_cast<int>(still_and_moving + off_colour))) {
    return true;
  }
  // Rising straight up (a serve's toss): min_travel up over fall_span_s or more, however slowly
  // (the newest points fit a flight with gravity's pull, above).
  if (travelled && options_.toss_max_lean > 0.0 && span >= options_.fall_span_s &&
      travel.z() >= options_.min_travel &&
      travel.head<2>().norm() <= options_.toss_max_lean * travel.z()) {
    return true;
  }
  // Falling: z = a + b t + c t^2 by least squares, c against -g/2.
  if (span < options_.fall_span_s || n < options_.fall_points) return false;
  Eigen::MatrixXd a(points.size(), 3);
  Eigen::VectorXd z(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double t = ToSeconds(points[i].t - points.front().t);
    a.row(i) << 1.0, t, t * t;
    z(i) = points[i].measurement.position.z();
  }
  const Eigen::Vector3d fit = a.colPivHouseholderQr().solve(z);
  const double rms = std::sqrt((a * fit - z).squaredNorm() / static_cast<double>(points.size()));
  const double half_g = 0.5 * options_.gravity;
  // The heights' noise, and what it leaves of the curvature (its sigma by least squares).
  double sigma_z = 0.0;
  for (const TrackletPoint& p : newest) {
    sigma_z = std::max(sigma_z, std::sqrt(std::max(0.0, p.measurement.covariance(2, 2))));
  }
  const Eigen::Matrix3d normal = a.transpose() * a;
  const double curvature_sigma = sigma_z * std::sqrt(std::max(0.0, normal.inverse()(2, 2)));
  // A ball's fall is a flight in all three axes: every point lies on one (heights that rise and
  // fall by chance, of pieces of a shirt's edge jumping sideways, fit gravity's curvature too).
  return std::abs(fit(2) + half_g) <= options_.fall_tolerance * half_g && rms <= 2.0 * sigma_z &&
         curvature_sigma <= options_.fall_max_curvature_sigma && FitsOneFlight(points);
}

std::optional<Tracklet> TrackInitiator::Push(TimeNs t, std::span<const TrackletPoint> candidates) {
  // Tracklets that waited too long end; points too old slide out.
  // The time-stamps' period, the shortest interval pushed: at 30 fps or slower max_missed
  // frames take longer than max_gap_s, and the count of time-stamps is what bounds the gap.
  if (last_t_ && (period_ == 0 || t - *last_t_ < period_)) period_ = t - *last_t_;
  last_t_ = t;
  const TimeNs max_span = FromSeconds(options_.max_span_s);
  const int64_t stamp = ++stamps_;
  std::erase_if(tracklets_, [&](const Tracklet& k) {
    const int missed = k.points.back().measurement.cameras >= 2 ? options_.max_missed
                                                                : options_.max_missed_one_view;
    const TimeNs max_gap =
        std::max(FromSeconds(options_.max_gap_s),
                 static_cast<TimeNs>(static_cast<double>(period_) * (missed + 1.5)));
    return t - k.points.back().t > max_gap || stamp - k.points.back().stamp > missed + 1;
  });
  for (Tracklet& k : tracklets_) {
    const auto old = std::find_if(k.points.begin(), k.points.end(),
                                  [&](const TrackletPoint& p) { return t - p.t <= max_span; });
    k.points.erase(k.points.begin(), old);
  }
  std::erase_if(tracklets_, [](const Tracklet& k) { return k.points.empty(); });

  // Every (tracklet, candidate) pair within the gate; longer tracklets choose first, then the
  // nearest pairs. A candidate extends one tracklet at most.
  struct Pair {
    int tracklet, candidate, rank;
    double distance;
  };
  std::vector<Pair> pairs;
  for (int i = 0; i < static_cast<int>(tracklets_.size()); ++i) {
    const Gate gate = Predict(tracklets_[i], t);
    const int rank = std::min<int>(3, static_cast<int>(tracklets_[i].points.size()));
    for (int j = 0; j < static_cast<int>(candidates.size()); ++j) {
      const double d =
          Scaled(gate.axes, gate.radii, candidates[j].measurement.position - gate.centre);
      if (d <= 1.0) pairs.push_back({i, j, rank, d});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return std::tie(b.rank, a.distance) < std::tie(a.rank, b.distance);
  });
  std::vector<bool> tracklet_taken(tracklets_.size(), false);
  std::vector<int> extended_rank(candidates.size(), 0);  // of the tracklet a candidate extended
  for (const Pair& p : pairs) {
    if (tracklet_taken[p.tracklet] || extended_rank[p.candidate] > 0) continue;
    tracklet_taken[p.tracklet] = true;
    extended_rank[p.candidate] = p.rank;
    tracklets_[p.tracklet].points.push_back(candidates[p.candidate]);
    tracklets_[p.tracklet].points.back().stamp = stamp;
  }
  // Every candidate that did not extend a tracklet of two points or more also starts one of its
  // own (a stray that took the ball's first point must not cost the ball its tracklet).
  // (Tracklets not extended at t keep waiting, up to max_gap_s.)
  for (int j = 0; j < static_cast<int>(candidates.size()); ++j) {
    if (extended_rank[j] < 2) {
      tracklets_.push_back(Tracklet{{candidates[j]}});
      tracklets_.back().points.back().stamp = stamp;
    }
  }
  if (static_cast<int>(tracklets_.size()) > options_.max_tracklets) {
    // Keep the longest.
    std::stable_sort(
        tracklets_.begin(), tracklets_.end(),
        [](const Tracklet& a, const Tracklet& b) { return a.points.size() > b.points.size(); });
    tracklets_.resize(options_.max_tracklets);
  }
  return TakeConfirmed(t, false);
}

std::optional<Tracklet> TrackInitiator::TakeConfirmed(TimeNs t, bool at_end) {
  // The longest confirmed tracklet that ends at t.
  int best = -1;
  for (int i = 0; i < static_cast<int>(tracklets_.size()); ++i) {
    const Tracklet& k = tracklets_[i];
    if (k.points.back().t != t || !Confirmed(k, at_end)) continue;
    if (best < 0 || k.points.size() > tracklets_[best].points.size()) best = i;
  }
  if (best < 0) return std::nullopt;
  Tracklet confirmed = std::move(tracklets_[best]);
  tracklets_.erase(tracklets_.begin() + best);
  confirmed.flight_start = FlightStart(confirmed);
  // Tracklets that share a point with it are the same ball, a step behind: they go with it.
  const auto shares = [&](const Tracklet& k) {
    for (const TrackletPoint& p : k.points) {
      for (const TrackletPoint& q : confirmed.points) {
        if (p.t == q.t && p.detections == q.detections) return true;
      }
    }
    return false;
  };
  std::erase_if(tracklets_, shares);
  return confirmed;
}

void TrackInitiator::NotTheBall(std::span<const FallPoint> taken, double radius) {
  for (Tracklet& k : tracklets_) {
    for (const TrackletPoint& p : k.points) {
      k.not_ball = k.not_ball || std::any_of(taken.begin(), taken.end(), [&](const FallPoint& q) {
                     return q.t == p.t && (q.position - p.measurement.position).norm() <= radius;
                   });
    }
  }
}

std::optional<Tracklet> TrackInitiator::Finish() {
  if (!last_t_) return std::nullopt;
  std::optional<Tracklet> confirmed = TakeConfirmed(*last_t_, true);
  if (confirmed) tracklets_.clear();
  return confirmed;
}

}  // namespace p4::track
