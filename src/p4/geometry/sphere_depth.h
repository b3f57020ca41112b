// The ball's position from one camera by its known diameter (paper §3.2, Figure 5, equation 1).
//
// The ball images as an ellipse; the paper takes its edges at p_e - x and p_e + x along the
// image radius and computes the half-angle alpha it subtends, then d = r / sin(alpha). We do the
// same with rays through the two edge points (so lens distortion is handled), and place the
// centre on the bisector of the two edge rays — the axis of the viewing cone — which removes
// the ellipse-centre bias the paper neglects (its "p = p_e" approximation).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "p4/geometry/camera.h"

namespace p4 {

struct SphereDepthResult {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // world, metres
  double distance = 0.0;    // from the optical centre to the ball centre, metres
  double half_angle = 0.0;  // alpha, radians
};

// centroid_px: centroid of the ball's image (distorted pixels); diameter_px: its diameter in
// pixels (e.g. 2 sqrt(area / pi)); ball_radius: metres. nullopt for a non-positive or
// non-finite diameter, or a diameter so large the camera would be inside the ball.
std::optional<SphereDepthResult> PointFromSphereImage(const Camera& camera,
                                                      const Eigen::Vector2d& centroid_px,
                                                      double diameter_px, double ball_radius);

}  // namespace p4
