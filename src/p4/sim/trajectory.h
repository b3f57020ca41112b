// The true ball motion of a simulated scene, sampled at the physics step and interpolated at any
// time (camera exposures, truth rows). Impacts are stored as two samples at the same instant
// (before, after), so interpolation never smooths a bounce. Between segments the ball is absent
// (not in the scene).
#pragma once

#include <optional>
#include <vector>

#include "p4/sim/ball_physics.h"

namespace p4::sim {

struct TrajectorySample {
  double t = 0.0;  // s
  BallState state;
  int segment = 0;
};

class Trajectory {
 public:
  // Samples must come in non-decreasing time. A new segment starts after EndSegment().
  void Append(double t, const BallState& state);
  void EndSegment();

  // Cubic Hermite interpolation of position (from positions and velocities), linear in velocity
  // and spin; nullopt when the ball is absent at t.
  std::optional<BallState> At(double t) const;

  const std::vector<TrajectorySample>& samples() const { return samples_; }
  double end_time() const { return samples_.empty() ? 0.0 : samples_.back().t; }

 private:
  std::vector<TrajectorySample> samples_;
  int segment_ = 0;
  bool segment_open_ = false;
};

}  // namespace p4::sim
