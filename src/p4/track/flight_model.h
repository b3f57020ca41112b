// The tracker's model of the ball in flight and at the table bounce, shared by the Kalman filter,
// the ball tracker and the monocular fit (never by the simulator, whose physics is the truth).
// World frame (z up), metres, seconds.
#pragma once

#include <Eigen/Core>

#include "p4/track/kalman_filter.h"

namespace p4::track {

struct FlightModel {
  double gravity = 9.81;
  double drag_per_mass = 0.1407;  // 1/m
  double ball_radius = 0.02;
  double restitution = 0.88;
  double friction = 0.25;
};

// One step of gravity and air drag (a = g - k |v| v, evaluated at the mid-step velocity: second
// order). Writes d a / d v at that velocity to *accel_jacobian when given.
Vector6d DragStep(const Vector6d& state, double dt, double gravity, double drag_per_mass,
                  Eigen::Matrix3d* accel_jacobian = nullptr);

// The linear map of the state at a table contact: vz -> -e vz, and friction takes
// mu (1 + e) |vz| of the horizontal speed, at most the 40 % that leaves a spinless ball rolling.
Matrix6d BounceMatrix(const Vector6d& at_contact, double restitution, double friction);

}  // namespace p4::track
