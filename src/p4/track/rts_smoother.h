// The Rauch-Tung-Striebel smoother over the ball filter's steps (kalman_filter.h): each step's
// prior (after the prediction), its posterior (after the update, or the prior when nothing was
// measured) and the Jacobian of the motion from the previous step's posterior to this prior.
// A smoothed step uses every measurement of its track, later ones too: a lone camera's view
// fixes only the ball's direction, and its depth along the ray, which the past alone leaves
// loose at 25 fps, is fixed by the two-view measurements on both sides.
// World frame (z up), metres, m/s; time-stamps int64 ns. Pure.
#pragma once

#include <span>
#include <vector>

#include "p4/core/time.h"
#include "p4/track/kalman_filter.h"

namespace p4::track {

struct FilterStep {
  TimeNs t = 0;
  Vector6d prior_state = Vector6d::Zero();
  Matrix6d prior_covariance = Matrix6d::Identity();
  Vector6d state = Vector6d::Zero();
  Matrix6d covariance = Matrix6d::Identity();
  Matrix6d transition = Matrix6d::Identity();  // d prior / d the previous step's posterior
  bool start = false;  // a track (re)started here: no link to the step before
  // The squared Mahalanobis distance of the measurement the step took from its prior (0: none):
  // a large one says the motion changed in a way the model does not know (a hit).
  double innovation_chi2 = 0.0;
};

struct SmoothedState {
  TimeNs t = 0;
  Vector6d state = Vector6d::Zero();
  Matrix6d covariance = Matrix6d::Identity();
};

// One smoothed state per step, in the steps' order (oldest first). Each track (from a start to
// the step before the next) is smoothed on its own; the steps before the first start are taken
// as one track.
std::vector<SmoothedState> SmoothSteps(std::span<const FilterStep> steps);

}  // namespace p4::track
