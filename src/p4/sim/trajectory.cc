#include "p4/sim/trajectory.h"

#include <algorithm>
#include <cassert>

namespace p4::sim {

void Trajectory::Append(double t, const BallState& state) {
  assert(samples_.empty() || t >= samples_.back().t);
  samples_.push_back({t, state, segment_});
  segment_open_ = true;
}

void Trajectory::EndSegment() {
  if (segment_open_) ++segment_;
  segment_open_ = false;
}

std::optional<BallState> Trajectory::At(double t) const {
  // First sample with time > t; the interval is [it - 1, it].
  const auto it =
      std::upper_bound(samples_.begin(), samples_.end(), t,
                       [](double value, const TrajectorySample& s) { return value < s.t; });
  if (it == samples_.begin() || it == samples_.end()) {
    if (it == samples_.end() && !samples_.empty() && samples_.back().t == t)
      return samples_.back().state;
    return std::nullopt;
  }
  const TrajectorySample& b = *it;
  const TrajectorySample& a = *(it - 1);
  if (a.segment != b.segment) return std::nullopt;
  const double h = b.t - a.t;
  if (h <= 0.0) return b.state;
  const double s = (t - a.t) / h;
  const double s2 = s * s, s3 = s2 * s;
  BallState out;
  out.position = (2 * s3 - 3 * s2 + 1) * a.state.position +
                 (s3 - 2 * s2 + s) * h * a.state.velocity + (-2 * s3 + 3 * s2) * b.state.position +
                 (s3 - s2) * h * b.state.velocity;
  out.velocity = (1 - s) * a.state.velocity + s * b.state.velocity;
  out.spin = (1 - s) * a.state.spin + s * b.state.spin;
  return out;
}

}  // namespace p4::sim
