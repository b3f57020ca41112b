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
};

std::vector<IdealTrack> ToIdeal(const Camera& camera, const std::vector<Track2d>& tracks) {
  std::vector<IdealTrack> out;
  for (const Track2d& track : tracks) {
    IdealTrack ideal;
    for (const TrackPoint& p : track.points) {
      ideal.t.push_back(p.t);
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
  const double h = 1e-4;  // s, for the derivative along time
  Eigen::Matrix2d normal = Eigen::Matrix2d::Identity();
  double weighted_squares = 0.0;
  int used = 0;
  bool fit_rate = false;
  for (int iteration = 0; iteration < 30; ++iteration) {
    Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    weighted_squares = 0.0;
    used = 0;
    double s_min = std::numeric_limits<double>::infinity(), s_max = -s_min;
    for (const LinePoint& p : points) {
      const double t = offset + rate * p.s;
      int track = -1;
      const auto r = Residual(ref, p, t, gap, -1, &track);
      if (!r || std::abs(*r) > 2.0 * options.inlier_px) continue;
      // The slope along the same track (another one's distance is no derivative).
      const auto r_plus = Residual(ref, p, t + h, gap, track);
      const auto r_minus = Residual(ref, p, t - h, gap, track);
      if (!r_plus || !r_minus) continue;
      const double d_offset = (*r_plus - *r_minus) / (2.0 * h);
      const Eigen::Vector2d j(d_offset, d_offset * p.s);
      const double w = std::abs(*r) <= options.huber_px ? 1.0 : options.huber_px / std::abs(*r);
      a += w * j * j.transpose();
      g += w * j * *r;
      weighted_squares += w * *r * *r;
      ++used;
      s_min = std::min(s_min, p.s), s_max = std::max(s_max, p.s);
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
  double squares = 0.0;
  for (const LinePoint& p : points) {
    const auto r = Residual(ref, p, offset + rate * p.s, gap);
    if (!r) continue;
    ++result.points;
    if (std::abs(*r) <= options.inlier_px) {
      ++result.agreements;
      squares += *r * *r;
    }
  }
  result.rms_px = result.agreements > 0 ? std::sqrt(squares / result.agreements) : 0.0;
  const int parameters = fit_rate ? 2 : 1;
  if (used > parameters && normal(0, 0) > 0.0) {
    const double variance = weighted_squares / (used - parameters);
    const double inverse = fit_rate ? normal.inverse()(0, 0) : 1.0 / normal(0, 0);
    result.sigma_s = std::sqrt(std::max(0.0, variance * inverse));
  }
  return result;
}

}  // namespace

bool OffsetOptions::IsValid(std::string* error) const {
  if (!(max_offset_s > 0.0) || !(bin_s > 0.0) || bin_s > max_offset_s || !(inlier_px > 0.0) ||
      !(huber_px > 0.0) || min_agreements < 3 || !(max_second_peak > 0.0) ||
      !(max_interpolation_gap_s > 0.0) || !(min_crossing_px >= 0.0) ||
      !(min_span_for_rate_s > 0.0) || !(in_step_sigmas >= 0.0)) {
    if (error) *error = "offset search: bounds must be positive, min_agreements >= 3";
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
  for (const Track2d& track : b_tracks) {
    for (const TrackPoint& p : track.points) {
      points.push_back({p.t, EpipolarLine(b, p.pixel, reference)});
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
  if (result.agreements < options.min_agreements) {
    result.why = fmt::format(
        "too little ball motion seen by both {} and {}: {} point(s) agree at the best offset "
        "({:+.4f} s), {} are needed; record a few seconds of play that both cameras see",
        reference.name, b.name, result.agreements, offset, options.min_agreements);
    return result;
  }
  if (result.peak_ratio > options.max_second_peak) {
    result.why = fmt::format(
        "the ball's motion fits two offsets of {} against {} almost as well ({:.0f} % of the "
        "points agree at the second); record a longer stretch of play",
        b.name, reference.name, 100.0 * result.peak_ratio);
    return result;
  }
  result.found = true;
  if (!result.rate_fitted && std::abs(offset) <= options.in_step_sigmas * result.sigma_s) {
    result.in_step = true;
    result.offset_s = 0.0;
  }
  return result;
}

}  // namespace p4::sync
