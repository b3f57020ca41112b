// The ball's position from one camera by its known diameter (paper §3.2, Figure 5, equation 1).
//
// The ball images as an ellipse; the paper takes its edges at p_e - x and p_e + x along the
// image radius and computes the half-angle alpha it subtends, then d = r / sin(alpha). We do the
// same with rays through the two edge points (so lens distortion is handled), and place the
// centre on the bisector of the two edge rays — the axis of the viewing cone — which removes
// the ellipse-centre bias the paper neglects (its "p = p_e" approximation).
//
// Off the optical axis the ellipse is longer along the image radius than across it (by 1/cos of
// the ray's angle to the axis): the axis measured must be named. The minor axis (across the
// radius) is the one motion blur leaves alone; taking it for the radial one puts the ball
// 1/cos(theta) too far (8 % at the edge of a 1280 px image with f = 1000 px).
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

enum class EllipseAxis {
  kAlongRadius,   // the major axis, along the image radius (the paper's x)
  kAcrossRadius,  // the minor axis, across it
};

// centroid_px: centroid of the ball's image (distorted pixels); diameter_px: the ellipse's
// diameter along `axis`, in pixels; ball_radius: metres. nullopt for a non-positive or
// non-finite diameter, or a diameter so large the camera would be inside the ball.
std::optional<SphereDepthResult> PointFromSphereImage(const Camera& camera,
                                                      const Eigen::Vector2d& centroid_px,
                                                      double diameter_px, EllipseAxis axis,
                                                      double ball_radius);

// The other way, to first order: the diameter (px) of a ball of `ball_radius` (m) centred at the
// world point, 2 r fx / depth; 0 at or behind the camera. What detectors expect to see there.
inline double SphereDiameterPx(const Camera& camera, const Eigen::Vector3d& world_point,
                               double ball_radius) {
  const double depth = (camera.cam_from_world * world_point).z();
  return depth > 0.0 ? 2.0 * ball_radius * camera.fx / depth : 0.0;
}

}  // namespace p4
