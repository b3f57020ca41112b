// The simulated players' aim: the racket velocity that sends the ball, with a given spin, to a
// chosen landing point. Solved by Newton iterations on the flight model (drag and Magnus,
// ignoring table outline and net; Levenberg-Marquardt), so the landing is exact for the simulator's
// own physics.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "p4/sim/ball_physics.h"

namespace p4::sim {

// A rally shot: land at (x, y) on the plane z = radius, crossing x = 0 at height net_z (centre).
struct RallyGoal {
  Eigen::Vector2d landing = Eigen::Vector2d::Zero();
  double net_z = 0.3;
};

// `start` holds the ball's position and the spin the racket gives it (its velocity is ignored).
// Returns the outgoing velocity, or nullopt when the solver does not converge to 1 mm.
std::optional<Eigen::Vector3d> SolveRallyShot(const BallState& start, const RallyGoal& goal,
                                              const BallParams& params);

// Velocity of the drag-free parabola from `from` to `to` in T seconds (a first guess).
Eigen::Vector3d BallisticVelocity(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double T,
                                  double gravity);

}  // namespace p4::sim
