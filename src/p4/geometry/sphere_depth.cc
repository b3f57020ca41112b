#include "p4/geometry/sphere_depth.h"

#include <algorithm>
#include <cmath>

namespace p4 {

std::optional<SphereDepthResult> PointFromSphereImage(const Camera& camera,
                                                      const Eigen::Vector2d& centroid_px,
                                                      double diameter_px, EllipseAxis axis,
                                                      double ball_radius) {
  if (!std::isfinite(diameter_px) || diameter_px <= 0.0 || ball_radius <= 0.0) return std::nullopt;
  // Direction of the image radius through the centroid (any direction at the principal point).
  Eigen::Vector2d radial(centroid_px.x() - camera.cx, centroid_px.y() - camera.cy);
  radial = radial.norm() > 1e-9 ? Eigen::Vector2d(radial.normalized()) : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d along =
      axis == EllipseAxis::kAlongRadius ? radial : Eigen::Vector2d(-radial.y(), radial.x());
  const Eigen::Vector2d edge_in = centroid_px - 0.5 * diameter_px * along;
  const Eigen::Vector2d edge_out = centroid_px + 0.5 * diameter_px * along;
  const Eigen::Vector3d ray_in = camera.RayDirection(edge_in);
  const Eigen::Vector3d ray_out = camera.RayDirection(edge_out);
  const double alpha = 0.5 * std::acos(std::clamp(ray_in.dot(ray_out), -1.0, 1.0));
  if (!(alpha > 0.0) || alpha >= M_PI / 2.0) return std::nullopt;
  SphereDepthResult result;
  result.half_angle = alpha;
  result.distance = ball_radius / std::sin(alpha);
  result.point = camera.Center() + result.distance * (ray_in + ray_out).normalized();
  return result;
}

}  // namespace p4
