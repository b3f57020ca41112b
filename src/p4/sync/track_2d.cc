#include "p4/sync/track_2d.h"

#include <algorithm>
#include <tuple>

#include "p4/core/robust.h"

namespace p4::sync {

bool Track2dOptions::IsValid(std::string* error) const {
  if (!(max_speed_px_s > 0.0) || !(gate_px > 0.0) || !(gate_speed_share >= 0.0) ||
      !(max_gap_s > 0.0) || min_points < 2 || !(min_travel_px >= 0.0)) {
    if (error) *error = "2D tracks: speeds, gates and the gap must be positive, min_points >= 2";
    return false;
  }
  return true;
}

std::vector<Track2d> LinkTracks(const std::vector<FrameCandidates>& frames,
                                const Track2dOptions& options) {
  std::vector<Track2d> kept, active;
  const auto close = [&](Track2d&& track) {
    if (static_cast<int>(track.points.size()) >= options.min_points &&
        (track.points.back().pixel - track.points.front().pixel).norm() >= options.min_travel_px) {
      kept.push_back(std::move(track));
    }
  };
  std::vector<std::tuple<double, int, int>> pairs;  // (distance, track, candidate)
  std::vector<char> taken_track, taken_candidate;
  for (const FrameCandidates& frame : frames) {
    // Tracks that waited too long end.
    for (auto it = active.begin(); it != active.end();) {
      if (frame.t - it->points.back().t > options.max_gap_s) {
        close(std::move(*it));
        it = active.erase(it);
      } else {
        ++it;
      }
    }
    pairs.clear();
    for (int i = 0; i < static_cast<int>(active.size()); ++i) {
      const std::vector<TrackPoint>& p = active[i].points;
      const double dt = frame.t - p.back().t;
      if (!(dt > 0.0)) continue;
      Eigen::Vector2d predicted = p.back().pixel;
      double gate = options.gate_px + options.max_speed_px_s * dt;
      if (p.size() >= 2) {
        const TrackPoint& a = p[p.size() - 2];
        const Eigen::Vector2d velocity = (p.back().pixel - a.pixel) / (p.back().t - a.t);
        const Eigen::Vector2d step = velocity * dt;
        predicted += step;
        gate = options.gate_px + options.gate_speed_share * step.norm();
      }
      for (int k = 0; k < static_cast<int>(frame.pixels.size()); ++k) {
        const double d = (frame.pixels[k] - predicted).norm();
        if (d <= gate && (frame.pixels[k] - p.back().pixel).norm() <= options.max_speed_px_s * dt) {
          pairs.emplace_back(d, i, k);
        }
      }
    }
    std::sort(pairs.begin(), pairs.end());
    taken_track.assign(active.size(), 0);
    taken_candidate.assign(frame.pixels.size(), 0);
    for (const auto& [d, i, k] : pairs) {
      if (taken_track[i] || taken_candidate[k]) continue;
      taken_track[i] = taken_candidate[k] = 1;
      active[i].points.push_back({frame.t, frame.pixels[k]});
    }
    for (int k = 0; k < static_cast<int>(frame.pixels.size()); ++k) {
      if (!taken_candidate[k]) active.push_back(Track2d{{{frame.t, frame.pixels[k]}}});
    }
  }
  for (Track2d& track : active) close(std::move(track));
  std::sort(kept.begin(), kept.end(), [](const Track2d& a, const Track2d& b) {
    return a.points.front().t < b.points.front().t;
  });
  return kept;
}

namespace {

// 0 for no values.
double MedianOrZero(std::vector<double> values) {
  return values.empty() ? 0.0 : MedianInPlace(values);
}

}  // namespace

double FramePeriod(const std::vector<FrameCandidates>& frames) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < frames.size(); ++i) steps.push_back(frames[i].t - frames[i - 1].t);
  return MedianOrZero(std::move(steps));
}

double FramePeriod(const std::vector<Track2d>& tracks) {
  std::vector<double> steps;
  for (const Track2d& track : tracks) {
    for (std::size_t i = 1; i < track.points.size(); ++i) {
      steps.push_back(track.points[i].t - track.points[i - 1].t);
    }
  }
  return MedianOrZero(std::move(steps));
}

}  // namespace p4::sync
