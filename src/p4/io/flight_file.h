// Real ball flights from ../shared/data/trajectories/tt3d (columns Timestamp,X,Y,Z; X across the
// table, Y along it), converted to P4's world frame (x = Y, y = -X, z = Z) and shifted to start
// at `start_s`. Velocities are central differences; spin is unknown (zero). The flight's table
// bounces (local minima of z below 4 cm over the table) are returned as truth events.
#pragma once

#include <string>
#include <vector>

#include "p4/sim/match.h"
#include "p4/sim/trajectory.h"

namespace p4 {

struct RealFlight {
  sim::Trajectory trajectory;
  std::vector<sim::TruthEvent> bounces;
  double end_s = 0.0;
};

// Throws p4::Error naming the file and line for unreadable files or bad rows.
RealFlight ReadTt3dFlight(const std::string& path, double start_s);

}  // namespace p4
