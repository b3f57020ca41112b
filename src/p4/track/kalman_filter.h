// The ball's Kalman filter (paper §3.3): state x = (x, y, z, vx, vy, vz) in the world frame
// (metres, m/s), uniform motion A(dt) with gravity as control input B u (u = -g on z, our "up"
// axis; the paper's frame has y up), position measurements H = [I 0].
//
// Two models: the paper's (linear, fixed Q = 1e-5 I per step, R = 1.6e-3 I, i.e. a 4 cm
// measurement error) and P4's default, an extended filter that adds air drag (a = -k |v| v, the
// ball's known k/m) to the motion, scales Q with the time step from a white-noise acceleration
// (the Magnus force of an unknown spin) and takes R from each measurement's own covariance.
// Pure; time comes in as dt.
#pragma once

#include <Eigen/Core>
#include <string>

namespace p4::track {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct KalmanOptions {
  enum class Noise { kPaper, kAcceleration };
  Noise noise = Noise::kAcceleration;
  double gravity = 9.81;
  double paper_q = 1e-5;          // kPaper: Q = paper_q * I per step
  double paper_r = 1.6e-3;        // kPaper: R = paper_r * I (m^2)
  double accel_sigma = 8.0;       // kAcceleration: m/s^2 of unmodelled acceleration (spin)
  double drag_per_mass = 0.1407;  // kAcceleration: k/m of the drag, 1/m (3.8e-4 kg/m / 2.7 g)

  bool IsValid(std::string* error) const;
};

class KalmanFilter {
 public:
  explicit KalmanFilter(const KalmanOptions& options = {});

  // The paper's start: x0 = (0, 0, 0, 1, 1, 1), P0 = I.
  void ResetPaper();
  void Reset(const Vector6d& state, const Matrix6d& covariance);

  // x = A x + B u (+ drag); P = F P F^T + Q with F the Jacobian. dt in seconds (> 0).
  void Predict(double dt);
  // x = D x, P = D P D^T + extra: a linear map of the state (the table bounce), with the
  // uncertainty it adds.
  void Apply(const Matrix6d& d, const Matrix6d& extra_noise);
  // Kalman update with a position measurement and its covariance (kPaper ignores it and uses R).
  void Update(const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance);
  // Squared Mahalanobis distance of a measurement from the predicted position.
  double Mahalanobis2(const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance) const;

  const Vector6d& state() const { return x_; }
  const Matrix6d& covariance() const { return p_; }
  // The Jacobian of the state's motion since the last ResetTransition (the product of every
  // Predict's and Apply's), for a smoother (rts_smoother.h).
  const Matrix6d& transition() const { return transition_; }
  void ResetTransition() { transition_.setIdentity(); }
  const KalmanOptions& options() const { return options_; }

  // Matrices of the model for a step dt (for tests and for the paper's comparison).
  static Matrix6d TransitionMatrix(double dt);
  Vector6d ControlTerm(double dt) const;  // B u
  Matrix6d ProcessNoise(double dt) const;

 private:
  Eigen::Matrix3d MeasurementNoise(const Eigen::Matrix3d& covariance) const;

  KalmanOptions options_;
  Vector6d x_ = Vector6d::Zero();
  Matrix6d p_ = Matrix6d::Identity();
  Matrix6d transition_ = Matrix6d::Identity();
};

}  // namespace p4::track
