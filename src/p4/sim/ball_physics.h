// The "true world" of the simulator: a table-tennis ball under gravity, air drag and the Magnus
// force, bouncing on the table (restitution and friction that trade spin for velocity), touching
// the net and its posts, falling to the floor. Richer than any model the tracker uses (the
// tracker's Kalman filter knows gravity only): the two share no code.
//
// Frames and units: world frame of DESIGN.md (metres, seconds, z up); spin w in rad/s, a vector
// along the spin axis (right-hand rule). Constants: Tebbe et al. / TT3D, ITTF.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace p4::sim {

struct BallParams {
  double mass = 0.0027;        // kg
  double radius = 0.02;        // m
  double gravity = 9.81;       // m/s^2
  double drag_kd = 3.8e-4;     // F_drag = -k_d |v| v, kg/m
  double magnus_km = 4.86e-6;  // F_magnus = k_m (w x v), kg
  // Restitution falls with impact speed: e = table_restitution + restitution_slope * (4 m/s -
  // |v_n|), clamped to [0.5, 0.97]. 0.88 at 4 m/s; ~0.91 for a ball dropped from 30 cm, which
  // then rebounds to ~23 cm as the ITTF requires (2.3: 23-25 cm from 30.5 cm).
  double table_restitution = 0.88;
  double restitution_slope = 0.02;  // per m/s
  double table_friction = 0.25;     // Coulomb coefficient ball-table
  double floor_restitution = 0.7;
  double floor_friction = 0.4;
  double net_restitution = 0.15;  // the net is soft: the ball drops off it
  double cord_restitution = 0.4;  // the top cord and the posts are firmer

  bool IsValid(std::string* error) const;
};

struct BallState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
  Eigen::Vector3d spin = Eigen::Vector3d::Zero();      // rad/s
};

// Acceleration of the ball in flight (gravity, drag, Magnus).
Eigen::Vector3d FlightAcceleration(const BallState& state, const BallParams& params);

// One 4th-order Runge-Kutta step of free flight (spin is constant in flight).
BallState FlightStep(const BallState& state, double dt, const BallParams& params);

// The table's coefficient of restitution for a normal impact speed (m/s).
double TableRestitution(double normal_speed, const BallParams& params);

// Impact with a rigid plane of normal n (unit) through the contact point: normal velocity
// reversed and scaled by `restitution`; tangential impulse from Coulomb friction that ends in
// rolling when friction suffices (hollow sphere, I = 2/3 m r^2), changing spin too.
BallState Impact(const BallState& state, const Eigen::Vector3d& normal, double restitution,
                 double friction, const BallParams& params);

enum class Contact { kNone, kTable, kNet, kFloor };

struct ContactEvent {
  Contact kind = Contact::kNone;
  double time = 0.0;                                // s, exact to ~1 us
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // ball centre at contact
  BallState before;                                 // at `time`, just before the impact
  BallState after;                                  // at `time`, just after it
};

// Advances the ball by dt through the world (table top, net with cord and posts, floor),
// resolving at most one contact at its exact time. `t` is the time at `state`. The returned
// event has kind kNone when nothing was touched.
ContactEvent WorldStep(BallState* state, double t, double dt, const BallParams& params);

}  // namespace p4::sim
