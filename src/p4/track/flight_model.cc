#include "p4/track/flight_model.h"

#include <algorithm>
#include <cmath>

namespace p4::track {

Vector6d DragStep(const Vector6d& x, double dt, double gravity, double k,
                  Eigen::Matrix3d* accel_jacobian) {
  Eigen::Vector3d p = x.head<3>(), v = x.tail<3>();
  const Eigen::Vector3d v_mid =
      MidpointStep<double>(&p, &v, Eigen::Vector3d::Zero(), dt, gravity, k);
  Vector6d out;
  out << p, v;
  if (accel_jacobian) {
    const double speed = v_mid.norm();
    *accel_jacobian = -k * speed * Eigen::Matrix3d::Identity();
    if (speed > 1e-9) *accel_jacobian -= k * v_mid * v_mid.transpose() / speed;
  }
  return out;
}

Matrix6d BounceMatrix(const Vector6d& at, double restitution, double friction) {
  const double vh = std::hypot(at(3), at(4));
  const double loss =
      vh > 1e-6 ? std::min(friction * (1.0 + restitution) * std::abs(at(5)), 0.4 * vh) / vh : 0.0;
  Matrix6d d = Matrix6d::Identity();
  d(5, 5) = -restitution;
  d(3, 3) = d(4, 4) = 1.0 - loss;
  return d;
}

}  // namespace p4::track
