#include "p4/geometry/camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace p4 {

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d k;
  k << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

bool Camera::HasDistortion() const {
  for (double d : distortion) {
    if (d != 0.0) return true;
  }
  return false;
}

Eigen::Vector3d Camera::Center() const {
  return -(cam_from_world.rotation.transpose() * cam_from_world.translation);
}

Eigen::Vector2d Camera::Distort(const Eigen::Vector2d& n) const {
  const double k1 = distortion[0], k2 = distortion[1], p1 = distortion[2], p2 = distortion[3],
               k3 = distortion[4];
  const double x = n.x(), y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d Camera::Undistort(const Eigen::Vector2d& d) const {
  if (!HasDistortion()) return d;
  // Newton iterations on Distort(n) = d with a numerical Jacobian; converges in a few steps.
  Eigen::Vector2d n = d;
  for (int iter = 0; iter < 20; ++iter) {
    const Eigen::Vector2d f = Distort(n) - d;
    if (f.squaredNorm() < 1e-26) break;
    constexpr double kStep = 1e-7;
    Eigen::Matrix2d jac;
    jac.col(0) = (Distort(n + Eigen::Vector2d(kStep, 0.0)) - Distort(n)) / kStep;
    jac.col(1) = (Distort(n + Eigen::Vector2d(0.0, kStep)) - Distort(n)) / kStep;
    n -= jac.inverse() * f;
  }
  return n;
}

Eigen::Vector2d Camera::IdealPixelFromNormalized(const Eigen::Vector2d& n) const {
  return {fx * n.x() + cx, fy * n.y() + cy};
}

Eigen::Vector2d Camera::PixelFromNormalized(const Eigen::Vector2d& n) const {
  return IdealPixelFromNormalized(HasDistortion() ? Distort(n) : n);
}

Eigen::Vector2d Camera::NormalizedFromPixel(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d d((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  return Undistort(d);
}

std::optional<Eigen::Vector2d> Camera::Project(const Eigen::Vector3d& point_in_world) const {
  const Eigen::Vector3d p = cam_from_world * point_in_world;
  if (p.z() <= 1e-3) return std::nullopt;
  return PixelFromNormalized(p.head<2>() / p.z());
}

Eigen::Vector3d Camera::RayDirection(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d n = NormalizedFromPixel(pixel);
  return (cam_from_world.rotation.transpose() * Eigen::Vector3d(n.x(), n.y(), 1.0)).normalized();
}

bool Camera::InImage(const Eigen::Vector2d& pixel, double margin) const {
  return pixel.x() >= -0.5 + margin && pixel.y() >= -0.5 + margin &&
         pixel.x() < width - 0.5 - margin && pixel.y() < height - 0.5 - margin;
}

bool Camera::Sees(const Eigen::Vector3d& point_in_world, double margin) const {
  const auto pixel = Project(point_in_world);
  return pixel && InImage(*pixel, margin);
}

bool ValidateCamera(const Camera& camera, std::string* error) {
  std::ostringstream why;
  const auto finite = [](double v) { return std::isfinite(v); };
  if (camera.width <= 0 || camera.height <= 0) {
    why << "image_width/image_height must be positive (got " << camera.width << "x" << camera.height
        << ")";
  } else if (!finite(camera.fx) || !finite(camera.fy) || camera.fx <= 0.0 || camera.fy <= 0.0) {
    why << "camera_matrix: focal lengths must be positive and finite (fx=" << camera.fx
        << ", fy=" << camera.fy << ")";
  } else if (!finite(camera.cx) || !finite(camera.cy)) {
    why << "camera_matrix: principal point is not finite";
  } else if (!std::all_of(camera.distortion.begin(), camera.distortion.end(), finite)) {
    why << "distortion_coefficients: not finite";
  } else if (!camera.cam_from_world.rotation.allFinite()) {
    why << "rotation: not finite";
  } else if (!camera.cam_from_world.translation.allFinite()) {
    why << "translation: not finite";
  } else {
    const Eigen::Matrix3d& r = camera.cam_from_world.rotation;
    const double orth = (r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    const double det = r.determinant();
    if (orth > 1e-6 || std::abs(det - 1.0) > 1e-6) {
      why << "rotation: not a rotation matrix (|R R^T - I| = " << orth << ", det = " << det << ")";
    }
  }
  std::string message = why.str();
  if (message.empty()) ValidateCameraClock(camera.clock, &message);  // writes only on failure
  if (message.empty()) return true;
  if (error) *error = message;
  return false;
}

}  // namespace p4
