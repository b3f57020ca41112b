#include "p4/sync/offset_search.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "p4/geometry/epipolar.h"

namespace p4::sync {
namespace {

// A reference track in ideal pixels (epipolar lines live there).
struct IdealTrack {
  std::vector<double> t;
  std::vector<Eigen::Vector2d> px;
  std::vector<double> rows;  // the real pixels' rows (the rolling shutter's)
};

std::vector<IdealTrack> ToIdeal(const Camera& camera, const std::vector<Track2d>& tracks) {
  std::vector<IdealTrack> out;
  for (const Track2d& track : tracks) {
    IdealTrack ideal;
    for (const TrackPoint& p : track.points) {
      ideal.t.push_back(p.t);
      ideal.rows.push_back(p.pixel.y());
      ideal.px.push_back(camera.IdealPixelFromNormalized(camera.NormalizedFromPixel(p.pixel)));
    }
    out.push_back(std::move(ideal));
  }
  return out;
}

// b's points with their epipolar lines in the reference.
struct LinePoint {
  double s = 0.0;  // b's stamp
  Eigen::Vector3d line = Eigen::Vector3d::Zero();
  double row = 0.0;  // b's real pixel row
  int track = 0;     // which of b's tracks
};

// The reference's position at world time t on `track`, interpolated through the (up to) three
// points around t that lie within max_gap of each other.
std::optional<Eigen::Vector2d> At(const IdealTrack& track, double t, double max_gap) {
  const auto it = std::upper_bound(track.t.begin(), track.t.end(), t);
  if (it == track.t.begin() || it == track.t.end()) return std::nullopt;
  const auto i = static_cast<std::size_t>(it - track.t.begin()) - 1;  // t_i <= t < t_i+1
  const double t0 = track.t[i], t1 = track.t[i + 1];
  if (t1 - t0 > max_gap) return std::nullopt;
  // A third point on the nearer side makes it quadratic (a ball's path bends with gravity).
  std::size_t j = i + 1;  // the third point's index, if any
  bool third = false;
  if (t - t0 < t1 - t && i > 0 && t0 - track.t[i - 1] <= max_gap) {
    j = i - 1, third = true;
  } else if (i + 2 < track.t.size() && track.t[i + 2] - t1 <= max_gap) {
    j = i + 2, third = true;
  }
  if (!third) {
    const double f = (t - t0) / (t1 - t0);
    return (1.0 - f) * track.px[i] + f * track.px[i + 1];
  }
  const double ts[3] = {t0, t1, track.t[j]};
  const Eigen::Vector2d* ps[3] = {&track.px[i], &track.px[i + 1], &track.px[j]};
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (int a = 0; a < 3; ++a) {
    double w = 1.0;
    for (int b = 0; b < 3; ++b) {
      if (b != a) w *= (t - ts[b]) / (ts[a] - ts[b]);
    }
    p += w * *ps[a];
  }
  return p;
}

// The signed distance of the reference's track from b's line at world time t: of `only` when
// given, else of the track nearest the line (its index in *which); nullopt where none covers t.
std::optional<double> Residual(const std::vector<IdealTrack>& tracks, const LinePoint& point,
                               double t, double max_gap, int only = -1, int* which = nullptr) {
  std::optional<double> best;
  for (int k = 0; k < static_cast<int>(tracks.size()); ++k) {
    const IdealTrack& track = tracks[k];
    if ((only >= 0 && k != only) || track.t.empty() || t < track.t.front() || t > track.t.back()) {
      continue;
    }
    if (const auto p = At(track, t, max_gap)) {
      const double r = point.line.dot(p->homogeneous());
      if (!best || std::abs(r) < std::abs(*best)) {
        best = r;
        if (which) *which = k;
      }
    }
  }
  return best;
}

// The reference's row at world time t on `track` (linear between the points around t).
double RowAt(const IdealTrack& track, double t) {
  const auto it = std::upper_bound(track.t.begin(), track.t.end(), t);
  if (it == track.t.begin()) return track.rows.front();
  if (it == track.t.end()) return track.rows.back();
  const auto i = static_cast<std::size_t>(it - track.t.begin()) - 1;
  const double f = (t - track.t[i]) / (track.t[i + 1] - track.t[i]);
  return (1.0 - f) * track.rows[i] + f * track.rows[i + 1];
}

// One of b's points linearised for the robust fits: its epipolar distance r to the reference
// track at time t (a point farther than twice inlier_px is left out), the slope of r along time
// on the same track (another one's distance is no derivative), its Huber weight.
struct Linearised {
  double r = 0.0, slope = 0.0, weight = 1.0;
  int track = -1;
};

std::optional<Linearised> Linearise(const std::vector<IdealTrack>& ref, const LinePoint& p,
                                    double t, const OffsetOptions& options) {
  const double gap = options.max_interpolation_gap_s;
  const double h = 1e-4;  // s, for the derivative along time
  Linearised l;
  const auto r = Residual(ref, p, t, gap, -1, &l.track);
  if (!r || std::abs(*r) > 2.0 * options.inlier_px) return std::nullopt;
  const auto r_plus = Residual(ref, p, t + h, gap, l.track);
  const auto r_minus = Residual(ref, p, t - h, gap, l.track);
  if (!r_plus || !r_minus) return std::nullopt;
  l.r = *r;
  l.slope = (*r_plus - *r_minus) / (2.0 * h);
  l.weight = std::abs(*r) <= options.huber_px ? 1.0 : options.huber_px / std::abs(*r);
  return l;
}

// Counts b's points with a reference track at their time (result->points), those within
// inlier_px of its epipolar line (agreements) and their RMS distance; `time` gives a point's
// time in the reference's clock.
template <typename TimeOf>
void CountAgreements(const std::vector<IdealTrack>& ref, const std::vector<LinePoint>& points,
                     const TimeOf& time, double gap, double inlier_px, OffsetResult* result) {
  result->points = result->agreements = 0;
  double squares = 0.0;
  for (const LinePoint& p : points) {
    const auto r = Residual(ref, p, time(p), gap);
    if (!r) continue;
    ++result->points;
    if (std::abs(*r) <= inlier_px) {
      ++result->agreements;
      squares += *r * *r;
    }
  }
  result->rms_px = result->agreements > 0 ? std::sqrt(squares / result->agreements) : 0.0;
}

// The fine fit from a coarse offset: a scan of +-2 bins, then iteratively reweighted
// Gauss-Newton on the epipolar distances (the rate too over long recordings); the agreement and
// the offset's sigma at the end.
OffsetResult FitAround(const std::vector<IdealTrack>& ref, const std::vector<LinePoint>& points,
                       double coarse, const OffsetOptions& options) {
  OffsetResult result;
  const double gap = options.max_interpolation_gap_s;
  const auto cost = [&](double offset) {
    double sum = 0.0;
    const double cap = options.inlier_px * options.inlier_px;
    for (const LinePoint& p : points) {
      if (const auto r = Residual(ref, p, offset + p.s, gap)) sum += std::min(*r * *r, cap) - cap;
    }
    return sum;  // lower is better; points without the reference's track count 0
  };
  double offset = coarse, best = cost(coarse);
  for (double x = coarse - 2.0 * options.bin_s; x <= coarse + 2.0 * options.bin_s;
       x += 0.05 * options.bin_s) {
    if (const double c = cost(x); c < best) best = c, offset = x;
  }
  double rate = 1.0;
  Eigen::Matrix2d normal = Eigen::Matrix2d::Identity();
  double weighted_squares = 0.0;
  int used = 0;
  bool fit_rate = false;
  // Each of b's tracks' share of the gradient (its points' errors are alike: one ball, one
  // background, one lean of its lit side), for the offset's sigma below.
  int track_count = 0;
  for (const LinePoint& p : points) track_count = std::max(track_count, p.track + 1);
  std::vector<Eigen::Vector2d> per_track;
  for (int iteration = 0; iteration < 30; ++iteration) {
    Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    weighted_squares = 0.0;
    used = 0;
    per_track.assign(static_cast<std::size_t>(track_count), Eigen::Vector2d::Zero());
    double s_min = std::numeric_limits<double>::infinity(), s_max = -s_min;
    for (const LinePoint& p : points) {
      const auto l = Linearise(ref, p, offset + rate * p.s, options);
      if (!l) continue;
      const Eigen::Vector2d j(l->slope, l->slope * p.s);
      const Eigen::Vector2d score = l->weight * j * l->r;
      a += l->weight * j * j.transpose();
      g += score;
      weighted_squares += l->weight * l->r * l->r;
      ++used;
      s_min = std::min(s_min, p.s), s_max = std::max(s_max, p.s);
      per_track[static_cast<std::size_t>(p.track)] += score;
    }
    if (used < 3) break;
    fit_rate = s_max - s_min >= options.min_span_for_rate_s;
    normal = a;
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    if (fit_rate) {
      step = -a.ldlt().solve(g);
    } else if (a(0, 0) > 0.0) {
      step.x() = -g.x() / a(0, 0);
    }
    // Stay in the linear range: at most a bin a step.
    step.x() = std::clamp(step.x(), -options.bin_s, options.bin_s);
    offset += step.x();
    rate += step.y();
    if (std::abs(step.x()) < 1e-7 && std::abs(step.y()) < 1e-9) break;
  }
  result.offset_s = offset;
  result.rate = rate;
  result.rate_fitted = fit_rate;
  CountAgreements(
      ref, points, [&](const LinePoint& p) { return offset + rate * p.s; }, gap, options.inlier_px,
      &result);
  const int parameters = fit_rate ? 2 : 1;
  if (used > parameters && normal(0, 0) > 0.0) {
    const double variance = weighted_squares / (used - parameters);
    const double inverse = fit_rate ? normal.inverse()(0, 0) : 1.0 / normal(0, 0);
    result.sigma_s = std::sqrt(std::max(0.0, variance * inverse));
    // The points' errors are not independent: along one of b's tracks they share its lean
    // (the lit half, the encoder's chroma) and its blur. The sandwich over the tracks (each
    // track's gradient share one sample) holds that; the larger of the two is the sigma.
    int tracks = 0;
    Eigen::Matrix2d meat = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& score : per_track) {
      if (score.isZero()) continue;
      meat += score * score.transpose();
      ++tracks;
    }
    if (tracks > parameters) {
      const double correction = static_cast<double>(tracks) / (tracks - parameters);
      double clustered = 0.0;
      if (fit_rate) {
        const Eigen::Matrix2d bread = normal.inverse();
        clustered = (bread * meat * bread)(0, 0);
      } else {
        clustered = meat(0, 0) / (normal(0, 0) * normal(0, 0));
      }
      result.sigma_s = std::max(result.sigma_s, std::sqrt(std::max(0.0, correction * clustered)));
    }
  }
  return result;
}

// The line times' priors (s a row): b's and the reference's, each with its sigma.
struct LineTimePrior {
  double b = 0.0, b_sigma = 1.0, r = 0.0, r_sigma = 1.0;
};

// The line times of both cameras with the offset (and the rate when `start` fitted one), by
// iteratively reweighted Gauss-Newton from `start`: b's point at row v is at world time
// offset + rate * (s + L_b v); the reference's points move by L_r times their rows, which moves
// its track at time t by -L_r * row(t) along itself. Recounts the agreement and sigma.
OffsetResult FitLineTimes(const std::vector<IdealTrack>& ref, const std::vector<LinePoint>& points,
                          const OffsetResult& start, const LineTimePrior& prior,
                          const OffsetOptions& options) {
  const double gap = options.max_interpolation_gap_s;
  double offset = start.offset_s, rate = start.rate, lb = 0.0, lr = 0.0;
  const bool fit_rate = start.rate_fitted;
  using Vector4 = Eigen::Matrix<double, 4, 1>;
  using Matrix4 = Eigen::Matrix<double, 4, 4>;
  const auto shifted = [&](double line_time) {
    std::vector<IdealTrack> out = ref;
    for (IdealTrack& track : out) {
      for (std::size_t j = 0; j < track.t.size(); ++j) track.t[j] += line_time * track.rows[j];
      if (!std::is_sorted(track.t.begin(), track.t.end())) track = {};  // rows too far apart
    }
    return out;
  };
  Matrix4 normal = Matrix4::Identity();
  double weighted_squares = 0.0;
  int used = 0;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const std::vector<IdealTrack> moved = shifted(lr);
    Matrix4 a = Matrix4::Zero();
    Vector4 g = Vector4::Zero();
    weighted_squares = 0.0;
    used = 0;
    for (const LinePoint& p : points) {
      const double t = offset + rate * (p.s + lb * p.row);
      const auto l = Linearise(moved, p, t, options);
      if (!l) continue;
      const double d = l->slope;
      const Vector4 j(d, fit_rate ? d * p.s : 0.0, d * rate * p.row,
                      -d * RowAt(moved[l->track], t));
      a += l->weight * j * j.transpose();
      g += l->weight * j * l->r;
      weighted_squares += l->weight * l->r * l->r;
      ++used;
    }
    if (used < 8) break;
    // The priors (options.readout_prior); the rate, when not fitted, stays.
    Matrix4 damped = a;
    damped(2, 2) += 1.0 / (prior.b_sigma * prior.b_sigma);
    damped(3, 3) += 1.0 / (prior.r_sigma * prior.r_sigma);
    g(2) += (lb - prior.b) / (prior.b_sigma * prior.b_sigma);
    g(3) += (lr - prior.r) / (prior.r_sigma * prior.r_sigma);
    if (!fit_rate) {  // the rate stays
      damped.row(1).setZero();
      damped.col(1).setZero();
      damped(1, 1) = 1.0;
      g(1) = 0.0;
    }
    normal = damped;
    Vector4 step = -damped.ldlt().solve(g);
    // Stay in the linear range: at most a bin a step (the line times in proportion).
    const double scale = std::min(1.0, options.bin_s / std::max(1e-12, std::abs(step(0))));
    step *= scale;
    offset += step(0), rate += step(1), lb += step(2), lr += step(3);
    if (std::abs(step(0)) < 1e-7 && std::abs(step(2)) < 1e-10 && std::abs(step(3)) < 1e-10) break;
  }
  OffsetResult result = start;
  if (used < 8) return result;  // too few points near the start: keep it
  result.offset_s = offset;
  result.rate = rate;
  result.line_times_fitted = true;
  result.line_time_s = lb;
  result.reference_line_time_s = lr;
  const std::vector<IdealTrack> moved = shifted(lr);
  CountAgreements(
      moved, points, [&](const LinePoint& p) { return offset + rate * (p.s + lb * p.row); }, gap,
      options.inlier_px, &result);
  const int parameters = fit_rate ? 4 : 3;
  if (used > parameters) {
    const double variance = weighted_squares / (used - parameters);
    const Matrix4 covariance = normal.inverse();
    result.sigma_s = std::sqrt(std::max(0.0, variance * covariance(0, 0)));
  }
  return result;
}

}  // namespace

bool OffsetOptions::IsValid(std::string* error) const {
  if (!(max_offset_s > 0.0) || !(bin_s > 0.0) || bin_s > max_offset_s || !(inlier_px > 0.0) ||
      !(huber_px > 0.0) || min_agreements < 3 || !(min_agreeing_s >= 0.0) ||
      !(max_second_peak > 0.0) || !(max_interpolation_gap_s > 0.0) || !(min_crossing_px >= 0.0) ||
      !(min_span_for_rate_s > 0.0) || !(in_step_sigmas >= 0.0) || !(readout_prior >= 0.0) ||
      readout_prior > 1.0 || !(readout_prior_sigma > 0.0)) {
    if (error)
      *error =
          "offset search: bounds must be positive, min_agreements >= 3, readout_prior in [0, 1]";
    return false;
  }
  return true;
}

OffsetResult FindOffset(const Camera& reference, const std::vector<Track2d>& reference_tracks,
                        const Camera& b, const std::vector<Track2d>& b_tracks,
                        const OffsetOptions& options) {
  OffsetResult result;
  const std::vector<IdealTrack> ref = ToIdeal(reference, reference_tracks);
  std::vector<LinePoint> points;
  for (int k = 0; k < static_cast<int>(b_tracks.size()); ++k) {
    for (const TrackPoint& p : b_tracks[k].points) {
      points.push_back({p.t, EpipolarLine(b, p.pixel, reference), p.pixel.y(), k});
    }
  }
  if (ref.empty() || points.empty()) {
    result.why = fmt::format("the ball was not seen moving ({} track(s) in {}, {} in {})",
                             ref.size(), reference.name, b_tracks.size(), b.name);
    return result;
  }
  // 1. Coarse: votes of every crossing.
  const int bins = 2 * static_cast<int>(std::ceil(options.max_offset_s / options.bin_s)) + 1;
  const int centre = bins / 2;
  std::vector<double> votes(static_cast<std::size_t>(bins), 0.0);
  for (const LinePoint& point : points) {
    for (const IdealTrack& track : ref) {
      for (std::size_t i = 0; i + 1 < track.t.size(); ++i) {
        const double dt = track.t[i + 1] - track.t[i];
        if (dt > options.max_interpolation_gap_s) continue;
        const double d0 = point.line.dot(track.px[i].homogeneous());
        const double d1 = point.line.dot(track.px[i + 1].homogeneous());
        if ((d0 <= 0.0) == (d1 <= 0.0) || std::abs(d0 - d1) < options.min_crossing_px) continue;
        const double crossing = track.t[i] + d0 / (d0 - d1) * dt;
        const int bin =
            centre + static_cast<int>(std::lround((crossing - point.s) / options.bin_s));
        if (bin >= 0 && bin < bins) votes[static_cast<std::size_t>(bin)] += 1.0;
      }
    }
  }
  // Smoothed over three bins (a crossing near a bin's edge).
  std::vector<double> smooth(votes.size(), 0.0);
  for (int i = 0; i < bins; ++i) {
    for (int k = std::max(0, i - 1); k <= std::min(bins - 1, i + 1); ++k) smooth[i] += votes[k];
  }
  // The highest peaks, each at least `exclusion` bins from the others.
  const int exclusion = std::max(5, static_cast<int>(std::ceil(0.01 / options.bin_s)));
  std::vector<int> peaks;
  {
    std::vector<int> order(static_cast<std::size_t>(bins));
    for (int i = 0; i < bins; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return smooth[a] > smooth[b]; });
    for (int i : order) {
      if (static_cast<int>(peaks.size()) >= options.peaks || smooth[i] <= 0.0) break;
      if (std::none_of(peaks.begin(), peaks.end(),
                       [&](int p) { return std::abs(p - i) <= exclusion; })) {
        peaks.push_back(i);
      }
    }
  }
  if (peaks.empty()) peaks.push_back(centre);
  // 2. Fine, from each peak: the one where most of b's points agree wins (a rally's back and
  // forth makes chance crossings repeat; the votes alone can favour a wrong period).
  std::vector<OffsetResult> fits;
  fits.reserve(peaks.size());
  for (int peak : peaks) {
    fits.push_back(FitAround(ref, points, (peak - centre) * options.bin_s, options));
  }
  std::sort(fits.begin(), fits.end(), [](const OffsetResult& a, const OffsetResult& b) {
    return a.agreements > b.agreements;
  });
  result = fits.front();
  // The runner-up must be a different offset (not the same one reached from a nearby peak).
  result.peak_ratio = 0.0;
  for (std::size_t k = 1; k < fits.size(); ++k) {
    if (std::abs(fits[k].offset_s - result.offset_s) > exclusion * options.bin_s) {
      result.peak_ratio =
          result.agreements > 0 ? static_cast<double>(fits[k].agreements) / result.agreements : 1.0;
      break;
    }
  }
  const double offset = result.offset_s;
  const double period_b = FramePeriod(b_tracks);
  const int needed =
      std::max(options.min_agreements,
               period_b > 0.0 ? static_cast<int>(std::ceil(options.min_agreeing_s / period_b)) : 0);
  if (result.agreements < needed) {
    result.why = fmt::format(
        "too little ball motion seen by both {} and {}: {} point(s) agree at the best offset "
        "({:+.4f} s), {} are needed; record a few seconds of play that both cameras see",
        reference.name, b.name, result.agreements, offset, needed);
    return result;
  }
  if (result.peak_ratio > options.max_second_peak) {
    result.why = fmt::format(
        "the ball's motion fits two offsets of {} against {} almost as well ({:.0f} % of the "
        "points agree at the second); record a longer stretch of play",
        b.name, reference.name, 100.0 * result.peak_ratio);
    return result;
  }
  if (options.fit_line_times) {
    // A whole frame's readout over the rows (s a row).
    const double full_b = period_b / std::max(1, b.height);
    const double full_r = FramePeriod(reference_tracks) / std::max(1, reference.height);
    // The fit adds to the line times the tracks' times hold already (the rig's).
    LineTimePrior prior;
    prior.b = options.readout_prior * full_b - b.clock.line_time_s;
    prior.r = options.readout_prior * full_r - reference.clock.line_time_s;
    prior.b_sigma = std::max(1e-9, options.readout_prior_sigma * full_b);
    prior.r_sigma = std::max(1e-9, options.readout_prior_sigma * full_r);
    result = FitLineTimes(ref, points, result, prior, options);
  }
  result.found = true;
  if (!result.rate_fitted && !result.line_times_fitted &&
      std::abs(offset) <= options.in_step_sigmas * result.sigma_s) {
    result.in_step = true;
    result.offset_s = 0.0;
  }
  return result;
}

}  // namespace p4::sync
