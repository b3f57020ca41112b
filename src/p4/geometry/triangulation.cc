#include "p4/geometry/triangulation.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace p4 {

bool TriangulationOptions::IsValid(std::string* error) const {
  if (!(min_conditioning >= 0.0 && min_conditioning < 1.0)) {
    if (error) *error = "min_conditioning must be in [0, 1)";
    return false;
  }
  if (!(min_depth >= 0.0)) {
    if (error) *error = "min_depth must be >= 0";
    return false;
  }
  if (!(pixel_sigma >= 0.0) || !(ray_sigma_m >= 0.0) || reweightings < 0) {
    if (error) *error = "pixel_sigma, ray_sigma_m and reweightings must be >= 0";
    return false;
  }
  return true;
}

std::optional<TriangulationResult> TriangulateRays(std::span<const Ray> rays,
                                                   const TriangulationOptions& options,
                                                   std::span<const double> weights) {
  if (rays.size() < 2 || (!weights.empty() && weights.size() != rays.size())) return std::nullopt;
  // Minimise sum w_i |(I - d d^T)(X - o)|^2  =>  (sum w_i P_i) X = sum w_i P_i o_i,
  // P_i = I - d_i d_i^T. The conditioning is the rays' own (sum P_i), whatever the weights.
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero(), weighted = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i];
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!(w > 0.0)) return std::nullopt;
    const Eigen::Matrix3d p =
        Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose();
    a += p;
    weighted += w * p;
    b += w * p * ray.origin;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(a);
  const Eigen::Vector3d& lambda = eigen.eigenvalues();  // ascending
  TriangulationResult result;
  result.conditioning = lambda(2) > 0.0 ? lambda(0) / lambda(2) : 0.0;
  if (!(result.conditioning >= options.min_conditioning) || lambda(0) <= 0.0) return std::nullopt;
  if (weights.empty()) {
    result.point =
        eigen.eigenvectors() * (eigen.eigenvectors().transpose() * b).cwiseQuotient(lambda);
  } else {
    result.point = weighted.ldlt().solve(b);
  }
  double sum_sq = 0.0;
  for (const Ray& ray : rays) {
    const Eigen::Vector3d to_point = result.point - ray.origin;
    const double depth = to_point.dot(ray.direction);
    if (depth < options.min_depth) return std::nullopt;
    sum_sq += (to_point - depth * ray.direction).squaredNorm();
  }
  result.rms_ray_distance = std::sqrt(sum_sq / static_cast<double>(rays.size()));
  return result;
}

double MeanReprojectionError(std::span<const Camera> cameras,
                             std::span<const Observation> observations,
                             const Eigen::Vector3d& point) {
  if (observations.empty()) return 0.0;
  double sum = 0.0;
  for (const Observation& obs : observations) {
    const auto projected = cameras[obs.camera].Project(point);
    sum += projected ? (*projected - obs.pixel).norm() : std::numeric_limits<double>::infinity();
  }
  return sum / static_cast<double>(observations.size());
}

std::optional<PointEstimate> TriangulateObservations(std::span<const Camera> cameras,
                                                     std::span<const Observation> observations,
                                                     const TriangulationOptions& options) {
  std::vector<Ray> rays;
  rays.reserve(observations.size());
  for (const Observation& obs : observations) {
    const Camera& camera = cameras[obs.camera];
    rays.push_back({camera.Center(), camera.RayDirection(obs.pixel)});
  }
  auto result = TriangulateRays(rays, options);
  if (!result) return std::nullopt;
  if (options.pixel_sigma > 0.0) {
    // Each ray's sigma in metres at the point: its pixels' at the range found last.
    std::vector<double> weights(rays.size());
    for (int pass = 0; pass < options.reweightings; ++pass) {
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const Camera& camera = cameras[observations[i].camera];
        const double range = (result->point - rays[i].origin).dot(rays[i].direction);
        const double across = options.pixel_sigma * range / (0.5 * (camera.fx + camera.fy));
        weights[i] = 1.0 / (across * across + options.ray_sigma_m * options.ray_sigma_m);
      }
      const auto weighted = TriangulateRays(rays, options, weights);
      if (!weighted) return std::nullopt;
      result = weighted;
    }
  }
  PointEstimate estimate;
  estimate.point = result->point;
  estimate.conditioning = result->conditioning;
  estimate.num_views = static_cast<int>(observations.size());
  estimate.mean_reprojection_px = MeanReprojectionError(cameras, observations, result->point);
  return estimate;
}

}  // namespace p4
