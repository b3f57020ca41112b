// The tracker's model of the ball in flight and at the table bounce, shared by the Kalman filter,
// the ball tracker and the stroke fit (never by the simulator, whose physics is the truth).
// World frame (z up), metres, seconds.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "p4/track/kalman_filter.h"

namespace p4::track {

struct FlightModel {
  double gravity = 9.81;
  double drag_per_mass = 0.1407;  // 1/m
  double ball_radius = 0.02;
  double restitution = 0.88;
  double friction = 0.25;
};

// One step h (either sign) of position p and velocity v under gravity, air drag and a Magnus
// acceleration b x v (a = g - k |v| v + b x v, evaluated at the mid-step velocity: second order).
// Returns that mid-step velocity. Templated for the stroke fit's automatic derivatives.
template <typename T>
Eigen::Matrix<T, 3, 1> MidpointStep(Eigen::Matrix<T, 3, 1>* p, Eigen::Matrix<T, 3, 1>* v,
                                    const Eigen::Matrix<T, 3, 1>& b, const T& h, double gravity,
                                    double drag_per_mass) {
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  const auto accel = [&](const Vec3& u) -> Vec3 {
    Vec3 a = -T(drag_per_mass) * u.norm() * u + b.cross(u);
    a.z() -= T(gravity);
    return a;
  };
  Vec3 v_mid = *v + T(0.5) * h * accel(*v);  // returned: not const (moved)
  const Vec3 a = accel(v_mid);
  *p = *p + h * *v + T(0.5) * h * h * a;
  *v = *v + h * a;
  return v_mid;
}

// One step of gravity and air drag (MidpointStep without spin). Writes d a / d v at the mid-step
// velocity to *accel_jacobian when given.
Vector6d DragStep(const Vector6d& state, double dt, double gravity, double drag_per_mass,
                  Eigen::Matrix3d* accel_jacobian = nullptr);

// The linear map of the state at a table contact: vz -> -e vz, and friction takes
// mu (1 + e) |vz| of the horizontal speed, at most the 40 % that leaves a spinless ball rolling.
Matrix6d BounceMatrix(const Vector6d& at_contact, double restitution, double friction);

}  // namespace p4::track
