// What the simulated cameras see: a sports hall (floor, walls with a barrier band, banners,
// lamps), a table with white lines on legs, the net with its white top band and posts, two
// player-like bodies, the ball (and maybe a spare one lying still), and optionally ArUco markers
// lying on the table's corners (paper §2); its colours and light come from a Look (look.h).
// World frame of DESIGN.md, metres.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "p4/sim/look.h"

namespace p4::sim {

// A square marker lying in the scene: corners in OpenCV's order (top-left, top-right,
// bottom-right, bottom-left of the marker image), cells x cells modules (border included),
// black[r * cells + c] = 1 for a black module.
struct MarkerQuad {
  int id = 0;
  std::array<Eigen::Vector3d, 4> corners;
  int cells = 6;
  std::vector<uint8_t> black;
};

struct SceneOptions {
  Look look;
  bool players = true;
  std::vector<MarkerQuad> markers;
};

// The dynamic content of one frame.
struct FrameContent {
  double t = 0.0;  // the frame's time, seconds (auto-exposure drift, arms)
  // Ball centres at evenly spaced instants over the exposure (empty: no ball in the scene).
  std::vector<Eigen::Vector3d> ball;
  // Feet positions (x, y) of player A and B.
  std::array<Eigen::Vector2d, 2> players{Eigen::Vector2d(-2.2, 0.0), Eigen::Vector2d(2.2, 0.0)};
};

// Where the markers of a calibration scene go: `size_m` squares lying on the table, 1 cm inside
// each of its four corners, ids 0-3 (A-left, A-right, B-left, B-right seen from A's end).
std::vector<MarkerQuad> TableCornerMarkers(double size_m);

}  // namespace p4::sim
