// The table-tennis table in the world frame of DESIGN.md: origin at the centre of the playing
// surface, x along the length (player A at x < 0, B at x > 0), y across, z up; metres.
// Dimensions follow the ITTF laws (2.74 m x 1.525 m, top 0.76 m above the floor, net 15.25 cm
// high whose ends stand 15.25 cm outside the side lines).
#pragma once

namespace p4::table {

inline constexpr double kLength = 2.74;
inline constexpr double kWidth = 1.525;
inline constexpr double kHalfLength = kLength / 2.0;
inline constexpr double kHalfWidth = kWidth / 2.0;
inline constexpr double kFloorZ = -0.76;
inline constexpr double kNetHeight = 0.1525;
inline constexpr double kNetHalfLength = kHalfWidth + 0.1525;  // posts at y = +-0.915
inline constexpr double kEdgeLineWidth = 0.02;
inline constexpr double kCentreLineWidth = 0.003;

// Ball (ITTF): 40 mm, 2.7 g.
inline constexpr double kBallRadius = 0.02;
inline constexpr double kBallDiameter = 2.0 * kBallRadius;
inline constexpr double kBallMass = 0.0027;

// True when (x, y) lies on the playing surface (edges included), or within `margin` (m) of it.
inline constexpr bool OnSurface(double x, double y, double margin = 0.0) {
  return x >= -kHalfLength - margin && x <= kHalfLength + margin && y >= -kHalfWidth - margin &&
         y <= kHalfWidth + margin;
}

// True when a ball whose centre crosses the net's plane (x = 0) at (y, z) meets the net: above
// the table, below the net's top plus its radius and `top_margin`, between the posts plus
// `side_margin` (the filter's prediction and the event detector draw these margins differently).
inline constexpr bool MeetsNet(double y, double z, double radius, double top_margin = 0.0,
                               double side_margin = 0.0) {
  return z >= 0.0 && z < kNetHeight + radius + top_margin &&
         (y < 0.0 ? -y : y) <= kNetHalfLength + side_margin;
}

// 'A' for the half at x < 0, 'B' for x >= 0.
inline constexpr char SideOf(double x) { return x < 0.0 ? 'A' : 'B'; }

}  // namespace p4::table
