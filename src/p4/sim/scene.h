// What the simulated cameras see: a sports hall (red-brown floor, walls with a dark barrier
// band), a blue table with white lines on legs, the net with its white top band and posts, two
// player-like bodies, the ball, and optionally ArUco markers lying on the table's corners
// (paper §2). World frame of DESIGN.md, metres.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

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
  bool orange_ball = true;  // else white
  bool players = true;
  bool orange_shirt = false;  // player B wears an orange-ish shirt (a hard distractor)
  std::vector<MarkerQuad> markers;
};

// The dynamic content of one frame.
struct FrameContent {
  // Ball centres at evenly spaced instants over the exposure (empty: no ball in the scene).
  std::vector<Eigen::Vector3d> ball;
  // Feet positions (x, y) of player A and B.
  std::array<Eigen::Vector2d, 2> players{Eigen::Vector2d(-2.2, 0.0), Eigen::Vector2d(2.2, 0.0)};
};

// Where the markers of a calibration scene go: `size_m` squares lying on the table, 1 cm inside
// each of its four corners, ids 0-3 (A-left, A-right, B-left, B-right seen from A's end).
std::vector<MarkerQuad> TableCornerMarkers(double size_m);

}  // namespace p4::sim
