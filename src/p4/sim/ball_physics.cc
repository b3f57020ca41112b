#include "p4/sim/ball_physics.h"

#include <algorithm>
#include <cmath>

#include "p4/core/table.h"

namespace p4::sim {

bool BallParams::IsValid(std::string* error) const {
  const auto fail = [&](const char* what) {
    if (error) *error = what;
    return false;
  };
  if (!(mass > 0.0)) return fail("mass must be positive");
  if (!(radius > 0.0)) return fail("radius must be positive");
  if (!(drag_kd >= 0.0) || !(magnus_km >= 0.0)) return fail("drag and Magnus must be >= 0");
  for (double e : {table_restitution, floor_restitution, net_restitution, cord_restitution}) {
    if (!(e >= 0.0 && e <= 1.0)) return fail("restitutions must be in [0, 1]");
  }
  if (!(table_friction >= 0.0) || !(floor_friction >= 0.0)) return fail("friction must be >= 0");
  return true;
}

Eigen::Vector3d FlightAcceleration(const BallState& s, const BallParams& p) {
  const Eigen::Vector3d& v = s.velocity;
  return Eigen::Vector3d(0.0, 0.0, -p.gravity) - (p.drag_kd / p.mass) * v.norm() * v +
         (p.magnus_km / p.mass) * s.spin.cross(v);
}

BallState FlightStep(const BallState& s, double dt, const BallParams& p) {
  const auto accel = [&](const Eigen::Vector3d& v) {
    BallState tmp = s;
    tmp.velocity = v;
    return FlightAcceleration(tmp, p);
  };
  const Eigen::Vector3d& x0 = s.position;
  const Eigen::Vector3d& v0 = s.velocity;
  const Eigen::Vector3d a1 = accel(v0);
  const Eigen::Vector3d v1 = v0 + 0.5 * dt * a1;
  const Eigen::Vector3d a2 = accel(v1);
  const Eigen::Vector3d v2 = v0 + 0.5 * dt * a2;
  const Eigen::Vector3d a3 = accel(v2);
  const Eigen::Vector3d v3 = v0 + dt * a3;
  const Eigen::Vector3d a4 = accel(v3);
  BallState out = s;
  out.position = x0 + dt / 6.0 * (v0 + 2.0 * v1 + 2.0 * v2 + v3);
  out.velocity = v0 + dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
  return out;
}

double TableRestitution(double normal_speed, const BallParams& p) {
  return std::clamp(p.table_restitution + p.restitution_slope * (4.0 - std::abs(normal_speed)), 0.5,
                    0.97);
}

BallState Impact(const BallState& s, const Eigen::Vector3d& n, double restitution, double friction,
                 const BallParams& p) {
  BallState out = s;
  const double vn = s.velocity.dot(n);
  if (vn >= 0.0) return out;  // separating already
  const double normal_impulse = p.mass * (1.0 + restitution) * (-vn);
  out.velocity -= (1.0 + restitution) * vn * n;
  // Velocity of the contact point (r = -R n from the centre), tangential part.
  const Eigen::Vector3d r = -p.radius * n;
  Eigen::Vector3d contact_velocity = s.velocity + s.spin.cross(r);
  contact_velocity -= contact_velocity.dot(n) * n;
  const double slip = contact_velocity.norm();
  if (slip > 1e-12) {
    // Impulse J (tangential) changes the contact velocity by J * 5 / (2 m) for I = 2/3 m R^2.
    const double stop_impulse = 0.4 * p.mass * slip;
    const double impulse = std::min(stop_impulse, friction * normal_impulse);
    const Eigen::Vector3d j = -impulse * contact_velocity / slip;
    const double inertia = 2.0 / 3.0 * p.mass * p.radius * p.radius;
    out.velocity += j / p.mass;
    out.spin += r.cross(j) / inertia;
  }
  return out;
}

namespace {

// Closest point of the net (the rectangle x = 0, |y| <= half length, 0 <= z <= height, the
// cord on top and the posts at its ends) to a point.
Eigen::Vector3d ClosestNetPoint(const Eigen::Vector3d& c) {
  return {0.0, std::clamp(c.y(), -table::kNetHalfLength, table::kNetHalfLength),
          std::clamp(c.z(), 0.0, table::kNetHeight)};
}

bool TouchesTable(const BallState& s, const BallParams& p) {
  return s.velocity.z() < 0.0 && s.position.z() < p.radius &&
         table::OnSurface(s.position.x(), s.position.y()) && s.position.z() > -p.radius;
}

bool TouchesNet(const BallState& s, const BallParams& p) {
  const Eigen::Vector3d d = s.position - ClosestNetPoint(s.position);
  return d.norm() < p.radius && s.velocity.dot(d) < 0.0;
}

bool TouchesFloor(const BallState& s, const BallParams& p) {
  return s.velocity.z() < 0.0 && s.position.z() < table::kFloorZ + p.radius;
}

Contact FirstContact(const BallState& s, const BallParams& p) {
  if (TouchesTable(s, p)) return Contact::kTable;
  if (TouchesNet(s, p)) return Contact::kNet;
  if (TouchesFloor(s, p)) return Contact::kFloor;
  return Contact::kNone;
}

}  // namespace

ContactEvent WorldStep(BallState* state, double t, double dt, const BallParams& p) {
  ContactEvent event;
  const BallState end = FlightStep(*state, dt, p);
  const Contact contact = FirstContact(end, p);
  if (contact == Contact::kNone) {
    *state = end;
    return event;
  }
  // Bisection for the first instant of contact inside the step.
  double lo = 0.0, hi = dt;
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (FirstContact(FlightStep(*state, mid, p), p) == Contact::kNone) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  BallState at = FlightStep(*state, hi, p);
  event.kind = contact;
  event.time = t + hi;
  event.point = at.position;
  event.before = at;
  switch (contact) {
    case Contact::kTable:
      at.position.z() = p.radius;
      at = Impact(at, Eigen::Vector3d::UnitZ(), TableRestitution(at.velocity.z(), p),
                  p.table_friction, p);
      break;
    case Contact::kFloor:
      at.position.z() = table::kFloorZ + p.radius;
      at = Impact(at, Eigen::Vector3d::UnitZ(), p.floor_restitution, p.floor_friction, p);
      break;
    case Contact::kNet: {
      const Eigen::Vector3d q = ClosestNetPoint(at.position);
      const Eigen::Vector3d n = (at.position - q).normalized();
      const bool on_face = q.z() < table::kNetHeight && std::abs(q.y()) < table::kNetHalfLength;
      at.position = q + p.radius * n;
      // The net face is a soft mesh (little rebound, much friction); cord and posts are firmer.
      at = Impact(at, n, on_face ? p.net_restitution : p.cord_restitution, on_face ? 0.6 : 0.3, p);
      if (on_face) at.velocity.y() *= 0.5;
      break;
    }
    case Contact::kNone:
      break;
  }
  event.after = at;
  // Finish the step in free flight (a second contact in the same step waits for the next one).
  *state = FlightStep(at, dt - hi, p);
  return event;
}

}  // namespace p4::sim
