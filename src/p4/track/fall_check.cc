#include "p4/track/fall_check.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

#include "p4/core/table.h"

namespace p4::track {
namespace {

constexpr double kMinVariance = 1e-6;  // m^2: (1 mm)^2, the weights' bound

}  // namespace

bool FallCheckOptions::IsValid(std::string* error) const {
  const std::pair<const char*, double> at_least_zero[] = {{"window_s", window_s},
                                                          {"table_margin", table_margin},
                                                          {"contact_share", contact_share},
                                                          {"max_spin", max_spin},
                                                          {"magnus_per_mass", magnus_per_mass},
                                                          {"fall_sigmas", fall_sigmas}};
  for (const auto& [name, value] : at_least_zero) {
    if (!(value >= 0.0)) {
      if (error) *error = std::string("fall check: ") + name + " must be >= 0";
      return false;
    }
  }
  if (!(fit_rms > 0.0)) {
    if (error) *error = "fall check: fit_rms must be > 0";
    return false;
  }
  return true;
}

double MostAirAcceleration(double speed, const FallCheckOptions& options, double drag_per_mass) {
  return options.magnus_per_mass * options.max_spin * speed + drag_per_mass * speed * speed;
}

double LeastFall(double speed, const FallCheckOptions& options, const FlightModel& model) {
  return model.gravity - MostAirAcceleration(speed, options, model.drag_per_mass);
}

FallFit JudgeFall(std::span<const FallPoint> points, const FallCheckOptions& options,
                  const FlightModel& model) {
  FallFit out;
  if (!(options.window_s > 0.0) || points.empty()) return out;
  const TimeNs newest = points.back().t;
  const auto first = std::find_if(points.begin(), points.end(), [&](const FallPoint& p) {
    return newest - p.t <= FromSeconds(options.window_s);
  });
  const auto window = points.subspan(static_cast<std::size_t>(first - points.begin()));
  // A window spanning most of window_s, with enough points for a parabola to mean something.
  if (window.size() < 5 || ToSeconds(newest - window.front().t) < 0.9 * options.window_s) {
    return out;
  }
  // Across a table contact the flight is two parabolas (or the ball rolls): no judgement. A
  // 25 fps camera's nearest sample to a bounce may be 20 ms from it: 8 cm above the table.
  for (const FallPoint& p : window) {
    const Eigen::Vector3d& q = p.position;
    if (table::OnSurface(q.x(), q.y()) && q.z() < model.ball_radius + options.table_margin) {
      return out;
    }
  }
  // p(t) = a + b t + c t^2 per axis by least squares weighted by the heights' variances (a view
  // of one camera, placed along its ray by its size, counts for little), t from the middle;
  // the window holds 5 points or more (n - 3 > 0).
  const TimeNs mid = window.front().t + (newest - window.front().t) / 2;
  const auto n = static_cast<Eigen::Index>(window.size());
  Eigen::MatrixXd a(n, 3);
  Eigen::MatrixXd p(n, 3);
  Eigen::VectorXd w(n);
  const double model_variance = options.fit_rms * options.fit_rms;
  for (Eigen::Index i = 0; i < n; ++i) {
    const FallPoint& f = window[static_cast<std::size_t>(i)];
    const double t = ToSeconds(f.t - mid);
    a.row(i) << 1.0, t, t * t;
    p.row(i) = f.position.transpose();
    w(i) = 1.0 / (std::max(f.covariance(2, 2), kMinVariance) + model_variance);
  }
  const Eigen::Matrix3d normal = a.transpose() * w.asDiagonal() * a;
  const Eigen::Matrix3d inverse = normal.inverse();
  const Eigen::MatrixXd fit = inverse * (a.transpose() * w.asDiagonal() * p);  // rows: a, b, c
  // One parabola per axis must explain the positions within their noise and fit_rms of model
  // error per axis (chi-square over 3 (n - 3) degrees of freedom within 3 of its sigmas): a
  // contact between the samples (a hit, a bounce) breaks it.
  const Eigen::MatrixXd residual = a * fit - p;
  double chi2 = 0.0;
  const Eigen::Matrix3d model_error = model_variance * Eigen::Matrix3d::Identity();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d r = residual.row(i).transpose();
    chi2 += r.dot((window[static_cast<std::size_t>(i)].covariance + model_error).ldlt().solve(r));
  }
  const double dof = 3.0 * static_cast<double>(n - 3);
  if (chi2 > dof + 3.0 * std::sqrt(2.0 * dof)) return out;
  out.fall = -2.0 * fit(2, 2);
  // Rising faster and faster (an upward acceleration over contact_share of g): a contact the
  // samples missed (a racket lifting a slow ball, a bounce off the table's edge), no judgement.
  if (out.fall < -options.contact_share * model.gravity) return out;
  out.judged = true;
  // The least fall of a ball as fast as the window's fastest end.
  const double half = 0.5 * ToSeconds(newest - window.front().t);
  out.speed = std::max((fit.row(1) - 2.0 * half * fit.row(2)).norm(),
                       (fit.row(1) + 2.0 * half * fit.row(2)).norm());
  out.least_fall = LeastFall(out.speed, options, model);
  // The curvature's sigma from the heights' variances, scaled up where the residuals say the
  // noise is larger than they.
  const Eigen::VectorXd height = residual.col(2);
  const double chi2_z = height.dot(w.asDiagonal() * height);
  const double scale = std::max(1.0, chi2_z / static_cast<double>(n - 3));
  out.fall_sigma = 2.0 * std::sqrt(std::max(0.0, inverse(2, 2)) * scale);
  out.not_falling = out.fall + options.fall_sigmas * out.fall_sigma < out.least_fall;
  return out;
}

}  // namespace p4::track
