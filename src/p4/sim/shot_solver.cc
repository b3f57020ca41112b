#include "p4/sim/shot_solver.h"

#include <Eigen/Dense>
#include <cmath>
#include <functional>

namespace p4::sim {
namespace {

constexpr double kDt = 0.002;
constexpr double kMaxFlight = 4.0;

// Landing points (crossings of z = radius, downward) and the height at the first crossing of
// x = 0. The first `bounces` landings bounce (no table outline, no net); after them the ball
// falls through, so every flight that moves towards the net has a crossing height (perhaps
// below the table), which keeps the residuals smooth for the solver.
struct Flight {
  Eigen::Vector2d landings[2];
  int num_landings = 0;
  double net_z = NAN;
};

Flight Fly(BallState s, const BallParams& p, int bounces = 0) {
  Flight flight;
  for (double t = 0.0; t < kMaxFlight; t += kDt) {
    const BallState next = FlightStep(s, kDt, p);
    if (std::isnan(flight.net_z) && (s.position.x() < 0.0) != (next.position.x() < 0.0)) {
      const double f = s.position.x() / (s.position.x() - next.position.x());
      flight.net_z = s.position.z() + f * (next.position.z() - s.position.z());
    }
    if (next.position.z() < p.radius && s.position.z() >= p.radius && next.velocity.z() < 0.0 &&
        flight.num_landings < 2) {
      const double f = (s.position.z() - p.radius) / (s.position.z() - next.position.z());
      const Eigen::Vector3d at = s.position + f * (next.position - s.position);
      flight.landings[flight.num_landings++] = at.head<2>();
      if (flight.num_landings <= bounces) {
        BallState bounced = next;
        bounced.position.z() = p.radius;
        s = Impact(bounced, Eigen::Vector3d::UnitZ(), TableRestitution(bounced.velocity.z(), p),
                   p.table_friction, p);
        continue;
      }
    }
    s = next;
    if (flight.num_landings > bounces && !std::isnan(flight.net_z)) break;
    if (s.position.z() < -1.0) break;  // below the floor: no landing will come
  }
  return flight;
}

// Levenberg-Marquardt on the 3 residuals with a forward-difference Jacobian; a candidate whose
// flight has no residual (e.g. never reaches the net) counts as a failed step.
std::optional<Eigen::Vector3d> Solve(
    const std::function<std::optional<Eigen::Vector3d>(const Eigen::Vector3d&)>& residual,
    Eigen::Vector3d v) {
  auto r = residual(v);
  if (!r) return std::nullopt;
  double lambda = 1e-3;
  for (int iter = 0; iter < 40; ++iter) {
    if (r->norm() < 1e-3) return v;
    Eigen::Matrix3d jac;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d dv = v;
      dv(k) += 1e-4;
      const auto rk = residual(dv);
      if (!rk) return std::nullopt;
      jac.col(k) = (*rk - *r) / 1e-4;
    }
    const Eigen::Matrix3d jtj = jac.transpose() * jac;
    const Eigen::Vector3d jtr = jac.transpose() * *r;
    bool improved = false;
    for (int k = 0; k < 10 && !improved; ++k) {
      Eigen::Matrix3d damped = jtj;
      damped.diagonal() += lambda * (jtj.diagonal().array() + 1e-9).matrix();
      const Eigen::Vector3d step = damped.ldlt().solve(-jtr);
      const auto rc = step.allFinite() ? residual(v + step) : std::nullopt;
      if (rc && rc->norm() < r->norm()) {
        v += step;
        r = rc;
        lambda = std::max(lambda * 0.3, 1e-7);
        improved = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) return std::nullopt;
  }
  return r->norm() < 1e-3 ? std::optional<Eigen::Vector3d>(v) : std::nullopt;
}

}  // namespace

Eigen::Vector3d BallisticVelocity(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double T,
                                  double gravity) {
  const Eigen::Vector3d d = to - from;
  return {d.x() / T, d.y() / T, d.z() / T + 0.5 * gravity * T};
}

std::optional<Eigen::Vector3d> SolveRallyShot(const BallState& start, const RallyGoal& goal,
                                              const BallParams& params) {
  const auto residual = [&](const Eigen::Vector3d& v) -> std::optional<Eigen::Vector3d> {
    BallState s = start;
    s.velocity = v;
    const Flight f = Fly(s, params);
    if (f.num_landings < 1 || std::isnan(f.net_z)) return std::nullopt;
    return Eigen::Vector3d(f.landings[0].x() - goal.landing.x(),
                           f.landings[0].y() - goal.landing.y(), f.net_z - goal.net_z);
  };
  const Eigen::Vector3d target(goal.landing.x(), goal.landing.y(), params.radius);
  // Try a few flight times for the starting guess: fast and flat to slow and high.
  for (double T : {0.35, 0.55, 0.8, 1.1}) {
    auto v = Solve(residual, BallisticVelocity(start.position, target, T, params.gravity));
    if (v) return v;
  }
  return std::nullopt;
}

}  // namespace p4::sim
