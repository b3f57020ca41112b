// Whether a track's recent measurements fall as a ball in flight can (beyond the paper): the
// ball in play flies under gravity, and air lifts it only so much. Drag lifts it by at most
// drag_per_mass v^2 (falling straight down), the Magnus force of a backspin by at most
// magnus_per_mass max_spin v (the simulator's k_m / m at 150 rev/s, the most a racket gives):
// below 5 m/s what the air can give is less than g (LeastFall), and a thing of the ball's colour
// that moves level at 2-4 m/s (a shoe, a shirt, a hand) does not fall as a ball that fast must.
// Above 5 m/s a backspin ball may fly level, and nothing is told.
//
// The measurements of the last window_s (time-stamps in ns, world frame of DESIGN.md, z up,
// metres) are fitted with one parabola per axis, weighted by the heights' variances; the fall is
// -2 c_z, its sigma that of the least-squares curvature (from the heights' variances, scaled up
// where the residuals are larger). Not judged: fewer than 5 points or less than 0.9 window_s,
// a point over the table within table_margin of it (a bounce, a rolling ball), a
// fit that the measurements' noise and fit_rms of model error per axis do not explain (a
// contact between the samples), heights accelerating upward by more than contact_share of g (a
// racket lifting a slow ball). Judged not falling: fall + fall_sigmas sigma < LeastFall(speed),
// the speed at the window's faster end. Pure.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>

#include "p4/core/time.h"
#include "p4/track/flight_model.h"

namespace p4::track {

struct FallCheckOptions {
  double window_s = 0.2;  // s of measurements judged; 0: never judged
  // m of model error per axis (beyond the measurements' noise) one parabola may have
  double fit_rms = 0.003;
  // m above the ball's radius: a window with a point over the table lower than this may hold a
  // bounce (or a ball rolling on it) and is not judged
  double table_margin = 0.08;
  // Nothing but a contact pushes the ball up: a window whose heights accelerate upward by more
  // than contact_share of gravity holds one (a hit between two samples) and is not judged.
  double contact_share = 0.5;
  // A fall fall_sigmas of its sigma below the least a ball as fast can have is no ball's.
  double max_spin = 942.0;          // rad/s
  double magnus_per_mass = 1.8e-3;  // (m/s^2) per (m/s) per (rad/s): k_m / m
  double fall_sigmas = 3.0;

  bool IsValid(std::string* error) const;
};

// One measurement of the window: its time, position and covariance (m^2).
struct FallPoint {
  TimeNs t = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity() * 1e-6;
};

// The fitted window (valid only when judged).
struct FallFit {
  bool judged = false;
  bool not_falling = false;  // judged, and it does not fall as a ball can
  double speed = 0.0;        // m/s, at the window's fastest end
  double fall = 0.0;         // m/s^2, downward
  double least_fall = 0.0;   // m/s^2, the least a ball as fast can fall
  double fall_sigma = 0.0;   // m/s^2
};

// The most acceleration (m/s^2) the air gives a ball in flight at `speed` (m/s), any direction:
// drag (drag_per_mass v^2) and the Magnus force of max_spin (magnus_per_mass max_spin v).
double MostAirAcceleration(double speed, const FallCheckOptions& options, double drag_per_mass);

// The least downward acceleration (m/s^2) of a ball in flight at `speed` (m/s): gravity less the
// most that drag and the Magnus force of max_spin lift it (negative above 5 m/s).
double LeastFall(double speed, const FallCheckOptions& options, const FlightModel& model);

// Judges the points (oldest first; those older than window_s before the newest are left out).
// Uses model.gravity, drag_per_mass and ball_radius.
FallFit JudgeFall(std::span<const FallPoint> points, const FallCheckOptions& options,
                  const FlightModel& model);

}  // namespace p4::track
