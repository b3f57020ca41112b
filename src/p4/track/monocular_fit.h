// The ball's flight from one camera (beyond the paper, whose one-camera depth by the diameter is
// "error-prone", §3.2): over a window of frames the ball's bearings from the camera, together
// with gravity, air drag and the table's bounce, fix its depth — a free flight seen from one
// place curves by g t^2 / 2 in metres, which sets the scale. Least squares (Levenberg-Marquardt)
// over the state at the window's first frame; the diameters enter as a weak prior on distance.
//
// Not yet used by the tracker: the spin of a real shot (Magnus) is not in the model, and an
// unknown acceleration breaks the gravity scale (see the test). World frame, metres, seconds.
// Pure.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

#include "p4/track/flight_model.h"
#include "p4/track/kalman_filter.h"

namespace p4::track {

// Propagates (x, y, z, vx, vy, vz) by dt under gravity and drag, reflecting at the table top.
Vector6d PropagateFlight(const Vector6d& state, double dt, const FlightModel& model);

struct BearingObservation {
  double t = 0.0;                                        // s
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // camera centre
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit ray to the ball
  double angle_sigma = 1e-3;                             // rad (pixel noise / focal length)
  double distance = 0.0;                                 // from the diameter (0: none)
  double distance_sigma = 1.0;                           // m
};

struct MonocularFit {
  Vector6d state = Vector6d::Zero();  // at the last observation's time
  Eigen::Matrix3d position_covariance = Eigen::Matrix3d::Identity();
  double rms_residual = 0.0;  // of the bearing residuals, in sigmas
};

// Preconditions: at least 4 observations in increasing time. `guess`: the state at the first
// observation's time (e.g. from the diameters). nullopt when the solve fails.
std::optional<MonocularFit> FitMonocularFlight(std::span<const BearingObservation> observations,
                                               const Vector6d& guess, const FlightModel& model);

}  // namespace p4::track
