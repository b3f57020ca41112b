#include "p4/track/kalman_filter.h"

#include <Eigen/Dense>

#include "p4/track/flight_model.h"

namespace p4::track {

bool KalmanOptions::IsValid(std::string* error) const {
  if (!(gravity >= 0.0) || !(paper_q > 0.0) || !(paper_r > 0.0) || !(accel_sigma > 0.0)) {
    if (error) *error = "Kalman noise parameters must be positive";
    return false;
  }
  return true;
}

KalmanFilter::KalmanFilter(const KalmanOptions& options) : options_(options) { ResetPaper(); }

void KalmanFilter::ResetPaper() {
  x_ << 0.0, 0.0, 0.0, 1.0, 1.0, 1.0;
  p_ = Matrix6d::Identity();
}

void KalmanFilter::Reset(const Vector6d& state, const Matrix6d& covariance) {
  x_ = state;
  p_ = covariance;
}

Matrix6d KalmanFilter::TransitionMatrix(double dt) {
  Matrix6d a = Matrix6d::Identity();
  a.topRightCorner<3, 3>() = dt * Eigen::Matrix3d::Identity();
  return a;
}

Vector6d KalmanFilter::ControlTerm(double dt) const {
  Vector6d bu = Vector6d::Zero();
  bu(2) = -0.5 * options_.gravity * dt * dt;
  bu(5) = -options_.gravity * dt;
  return bu;
}

Matrix6d KalmanFilter::ProcessNoise(double dt) const {
  if (options_.noise == KalmanOptions::Noise::kPaper)
    return options_.paper_q * Matrix6d::Identity();
  const double q = options_.accel_sigma * options_.accel_sigma;
  Matrix6d noise = Matrix6d::Zero();
  const Eigen::Matrix3d i3 = Eigen::Matrix3d::Identity();
  noise.topLeftCorner<3, 3>() = q * dt * dt * dt / 3.0 * i3;
  noise.topRightCorner<3, 3>() = q * dt * dt / 2.0 * i3;
  noise.bottomLeftCorner<3, 3>() = q * dt * dt / 2.0 * i3;
  noise.bottomRightCorner<3, 3>() = q * dt * i3;
  return noise;
}

void KalmanFilter::Predict(double dt) {
  Matrix6d f = TransitionMatrix(dt);
  const double k = options_.noise == KalmanOptions::Noise::kPaper ? 0.0 : options_.drag_per_mass;
  if (k == 0.0) {
    x_ = f * x_ + ControlTerm(dt);
  } else {
    Eigen::Matrix3d jac;
    x_ = DragStep(x_, dt, options_.gravity, k, &jac);
    f.topRightCorner<3, 3>() += 0.5 * dt * dt * jac;
    f.bottomRightCorner<3, 3>() += dt * jac;
  }
  p_ = f * p_ * f.transpose() + ProcessNoise(dt);
  transition_ = f * transition_;
}

void KalmanFilter::Apply(const Matrix6d& d, const Matrix6d& extra_noise) {
  x_ = d * x_;
  p_ = d * p_ * d.transpose() + extra_noise;
  transition_ = d * transition_;
}

Eigen::Matrix3d KalmanFilter::MeasurementNoise(const Eigen::Matrix3d& covariance) const {
  if (options_.noise == KalmanOptions::Noise::kPaper)
    return options_.paper_r * Eigen::Matrix3d::Identity();
  return covariance;
}

void KalmanFilter::Update(const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d s = p_.topLeftCorner<3, 3>() + MeasurementNoise(covariance);
  const Eigen::Matrix<double, 6, 3> k = p_.leftCols<3>() * s.inverse();  // P H^T S^-1
  x_ += k * (z - x_.head<3>());
  const Matrix6d i_kh =
      Matrix6d::Identity() -
      k * (Eigen::Matrix<double, 3, 6>() << Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero())
              .finished();
  p_ = i_kh * p_;
  p_ = 0.5 * (p_ + p_.transpose());
}

double KalmanFilter::Mahalanobis2(const Eigen::Vector3d& z,
                                  const Eigen::Matrix3d& covariance) const {
  const Eigen::Matrix3d s = p_.topLeftCorner<3, 3>() + MeasurementNoise(covariance);
  const Eigen::Vector3d r = z - x_.head<3>();
  return r.dot(s.ldlt().solve(r));
}

}  // namespace p4::track
