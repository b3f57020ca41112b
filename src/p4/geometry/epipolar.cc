#include "p4/geometry/epipolar.h"

#include <cmath>

namespace p4 {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

Eigen::Vector2d IdealPixel(const Camera& camera, const Eigen::Vector2d& pixel) {
  return camera.IdealPixelFromNormalized(camera.NormalizedFromPixel(pixel));
}

}  // namespace

Eigen::Matrix3d FundamentalMatrix(const Camera& camera_i, const Camera& camera_j) {
  const Rigid3d j_from_i = camera_j.cam_from_world * camera_i.cam_from_world.Inverse();
  const Eigen::Matrix3d essential = Skew(j_from_i.translation) * j_from_i.rotation;
  return camera_j.K().inverse().transpose() * essential * camera_i.K().inverse();
}

Eigen::Vector3d EpipolarLine(const Camera& camera_i, const Eigen::Vector2d& pixel_i,
                             const Camera& camera_j) {
  const Eigen::Vector2d ideal = IdealPixel(camera_i, pixel_i);
  Eigen::Vector3d line = FundamentalMatrix(camera_i, camera_j) * ideal.homogeneous();
  const double norm = line.head<2>().norm();
  return norm > 0.0 ? Eigen::Vector3d(line / norm) : line;
}

double EpipolarDistance(const Camera& camera_i, const Eigen::Vector2d& pixel_i,
                        const Camera& camera_j, const Eigen::Vector2d& pixel_j) {
  const Eigen::Vector3d line = EpipolarLine(camera_i, pixel_i, camera_j);
  return std::abs(line.dot(IdealPixel(camera_j, pixel_j).homogeneous()));
}

std::vector<Eigen::Vector2d> EpipolarCurve(const Camera& camera_i, const Eigen::Vector2d& pixel_i,
                                           const Camera& camera_j, double near_m, double far_m,
                                           int samples) {
  std::vector<Eigen::Vector2d> curve;
  const Eigen::Vector3d origin = camera_i.Center();
  const Eigen::Vector3d direction = camera_i.RayDirection(pixel_i);
  for (int k = 0; k < samples; ++k) {
    // Samples evenly spaced in inverse depth: even on the image of the ray.
    const double s = samples > 1 ? static_cast<double>(k) / (samples - 1) : 0.0;
    const double depth = 1.0 / ((1.0 - s) / near_m + s / far_m);
    const auto pixel = camera_j.Project(origin + depth * direction);
    if (pixel && camera_j.InImage(*pixel)) curve.push_back(*pixel);
  }
  return curve;
}

}  // namespace p4
