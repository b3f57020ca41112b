// Simulated play: serves and rallies between player A (x < 0) and player B (x > 0) that follow
// the laws of table tennis, each point ending in a way drawn at random (serve fault, net, out,
// missed return, double bounce). Players are invisible hitters: they aim the ball at a target
// with a speed of 5-25 m/s and up to ~150 rev/s of spin, and every planned shot is checked
// against the physics, so what the truth files say is what the ball did.
//
// Pure: randomness from the seed in the options, no clock, no files.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p4/game/event.h"
#include "p4/game/match_score.h"
#include "p4/sim/ball_physics.h"
#include "p4/sim/trajectory.h"

namespace p4::sim {

// One truth event (DESIGN.md events.jsonl): see game::Event.
using TruthEvent = game::Event;

struct MatchOptions {
  int points = 6;   // points to play (fewer if the match ends first)
  int best_of = 5;  // games
  char first_server = 'A';
  double start_s = 0.3;                      // time of the first toss
  double gap_s = 1.0;                        // ball out of the scene between points
  double physics_dt = 0.0005;                // integration step, s (<= 1 ms)
  double min_speed = 5.0, max_speed = 25.0;  // m/s of rally shots
  double max_spin_rps = 150.0;
  double continue_probability = 0.6;  // chance a rally goes on after each good return
  uint64_t seed = 1;
  BallParams ball;

  bool IsValid(std::string* error) const;
};

struct MatchResult {
  Trajectory trajectory;
  std::vector<TruthEvent> events;  // sorted by time
  game::MatchScore score;
  int points_played = 0;
  double duration = 0.0;  // s, end of the last segment plus the gap
};

MatchResult SimulateMatch(const MatchOptions& options);

}  // namespace p4::sim
