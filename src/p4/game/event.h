// One event of play (DESIGN.md events.jsonl), as the simulator's truth and the tracker's event
// detector and referee publish them. `position` (world, metres) is the ball centre for serve and
// hit; the contact point for bounce (on the table, z = 0), net and floor; and the landing point
// outside the table (z = 0) for out.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

namespace p4::game {

struct Event {
  double t = 0.0;    // seconds from the start of the recording
  std::string type;  // serve, hit, bounce, net, out, floor, point, let, game, match
  char player = 0;   // serve, hit: who struck the ball ('A': x < 0, 'B': x > 0)
  char side = 0;     // bounce: 'A' or 'B' half of the table
  std::optional<Eigen::Vector3d> position;
  std::optional<double> confidence;  // detected events: 0-1; truth: none
  char winner = 0;                   // point, game, match
  std::string reason;                // point
  std::array<int, 2> score{};        // point, game, match: points of A and B after it
  std::array<int, 2> games{};        // games of A and B after it
};

}  // namespace p4::game
