#include "p4/track/monocular_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "p4/core/table.h"

namespace p4::track {
Vector6d PropagateFlight(const Vector6d& state, double dt, const FlightModel& m) {
  Vector6d x = state;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(dt) / 0.002)));
  const double h = dt / steps;
  for (int i = 0; i < steps; ++i) {
    Vector6d next = DragStep(x, h, m.gravity, m.drag_per_mass);
    if (h > 0.0 && next(2) < m.ball_radius && x(2) >= m.ball_radius && next(5) < 0.0) {
      const double f = (x(2) - m.ball_radius) / (x(2) - next(2));
      Vector6d at = DragStep(x, f * h, m.gravity, m.drag_per_mass);
      if (table::OnSurface(at(0), at(1))) {
        at = BounceMatrix(at, m.restitution, m.friction) * at;
        next = DragStep(at, (1.0 - f) * h, m.gravity, m.drag_per_mass);
      }
    }
    x = next;
  }
  return x;
}

std::optional<MonocularFit> FitMonocularFlight(std::span<const BearingObservation> obs,
                                               const Vector6d& guess, const FlightModel& model) {
  const int n = static_cast<int>(obs.size());
  if (n < 4) return std::nullopt;
  const int rows = 3 * n;
  // Residuals: two angular components per bearing (in sigmas) and the distance prior.
  const auto residuals = [&](const Vector6d& x0, Eigen::VectorXd* r) {
    r->resize(rows);
    Vector6d x = x0;
    double t = obs[0].t;
    for (int i = 0; i < n; ++i) {
      x = PropagateFlight(x, obs[i].t - t, model);
      t = obs[i].t;
      const Eigen::Vector3d to = x.head<3>() - obs[i].origin;
      const double range = std::max(0.05, to.norm());
      const Eigen::Vector3d d = obs[i].direction;
      const Eigen::Vector3d e1 = d.unitOrthogonal();
      const Eigen::Vector3d e2 = d.cross(e1);
      (*r)(3 * i) = e1.dot(to) / range / obs[i].angle_sigma;
      (*r)(3 * i + 1) = e2.dot(to) / range / obs[i].angle_sigma;
      (*r)(3 * i + 2) =
          obs[i].distance > 0.0 ? (range - obs[i].distance) / obs[i].distance_sigma : 0.0;
    }
  };
  // Start from the guess, or from a straight fit of the diameters' positions (gravity removed)
  // when that explains the bearings better.
  Vector6d x = guess;
  {
    Eigen::MatrixXd a(3 * n, 6);
    Eigen::VectorXd b(3 * n);
    a.setZero();
    for (int i = 0; i < n; ++i) {
      const double dt = obs[i].t - obs[0].t;
      const double dist = obs[i].distance > 0.0 ? obs[i].distance : 3.0;
      Eigen::Vector3d q = obs[i].origin + dist * obs[i].direction;
      q.z() += 0.5 * model.gravity * dt * dt;
      a.block<3, 3>(3 * i, 0) = Eigen::Matrix3d::Identity();
      a.block<3, 3>(3 * i, 3) = dt * Eigen::Matrix3d::Identity();
      b.segment<3>(3 * i) = q;
    }
    const Vector6d line = a.colPivHouseholderQr().solve(b);
    Eigen::VectorXd r_guess, r_line;
    residuals(x, &r_guess);
    residuals(line, &r_line);
    if (line.allFinite() && r_line.squaredNorm() < r_guess.squaredNorm()) x = line;
  }
  Eigen::VectorXd r, rc;
  residuals(x, &r);
  double lambda = 1e-3;
  Eigen::MatrixXd jac(rows, 6);
  for (int iter = 0; iter < 30; ++iter) {
    for (int k = 0; k < 6; ++k) {
      Vector6d xk = x;
      const double h = k < 3 ? 1e-5 : 1e-4;
      xk(k) += h;
      residuals(xk, &rc);
      jac.col(k) = (rc - r) / h;
    }
    const Matrix6d jtj = jac.transpose() * jac;
    const Vector6d jtr = jac.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Matrix6d damped = jtj;
      damped.diagonal() += lambda * (jtj.diagonal().array() + 1e-9).matrix();
      const Vector6d step = damped.ldlt().solve(-jtr);
      if (!step.allFinite()) return std::nullopt;
      residuals(x + step, &rc);
      if (rc.squaredNorm() < r.squaredNorm()) {
        x += step;
        const bool converged = r.squaredNorm() - rc.squaredNorm() < 1e-8 * (1.0 + r.squaredNorm());
        r = rc;
        lambda = std::max(1e-9, lambda * 0.3);
        improved = true;
        if (converged) iter = 1000;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;
  }
  if (!x.allFinite()) return std::nullopt;
  MonocularFit fit;
  // Covariance at the first time from the normal equations, carried to the last time through
  // the (numeric) Jacobian of the propagation.
  const Matrix6d info = jac.transpose() * jac;
  const Matrix6d cov0 = info.ldlt().solve(Matrix6d::Identity());
  const double span = obs[n - 1].t - obs[0].t;
  fit.state = PropagateFlight(x, span, model);
  Matrix6d f;
  for (int k = 0; k < 6; ++k) {
    Vector6d xk = x;
    const double h = k < 3 ? 1e-5 : 1e-4;
    xk(k) += h;
    f.col(k) = (PropagateFlight(xk, span, model) - fit.state) / h;
  }
  fit.position_covariance = (f * cov0 * f.transpose()).topLeftCorner<3, 3>();
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += r(3 * i) * r(3 * i) + r(3 * i + 1) * r(3 * i + 1);
  fit.rms_residual = std::sqrt(sum / (2.0 * n));
  return fit;
}

}  // namespace p4::track
