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

namespace {

// The rays' distances to `point`: false when it lies behind (or within min_depth of) a ray's
// origin; else their RMS into `result`.
bool RayDistances(std::span<const Ray> rays, const TriangulationOptions& options,
                  TriangulationResult* result) {
  double sum_sq = 0.0;
  for (const Ray& ray : rays) {
    const Eigen::Vector3d to_point = result->point - ray.origin;
    const double depth = to_point.dot(ray.direction);
    if (depth < options.min_depth) return false;
    sum_sq += (to_point - depth * ray.direction).squaredNorm();
  }
  result->rms_ray_distance = std::sqrt(sum_sq / static_cast<double>(rays.size()));
  return true;
}

// The point minimising sum w_i |(I - d_i d_i^T)(X - o_i)|^2 (one positive weight per ray;
// the rays' conditioning checked by the caller).
Eigen::Vector3d WeightedPoint(std::span<const Ray> rays, std::span<const double> weights) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Eigen::Matrix3d p = weights[i] * (Eigen::Matrix3d::Identity() -
                                            rays[i].direction * rays[i].direction.transpose());
    a += p;
    b += p * rays[i].origin;
  }
  return a.ldlt().solve(b);
}

}  // namespace

std::optional<TriangulationResult> TriangulateRays(std::span<const Ray> rays,
                                                   const TriangulationOptions& options) {
  if (rays.size() < 2) return std::nullopt;
  // Minimise sum |(I - d d^T)(X - o)|^2  =>  (sum P_i) X = sum P_i o_i, P_i = I - d_i d_i^T.
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const Ray& ray : rays) {
    const Eigen::Matrix3d p =
        Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose();
    a += p;
    b += p * ray.origin;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(a);
  const Eigen::Vector3d& lambda = eigen.eigenvalues();  // ascending
  TriangulationResult result;
  result.conditioning = lambda(2) > 0.0 ? lambda(0) / lambda(2) : 0.0;
  if (!(result.conditioning >= options.min_conditioning) || lambda(0) <= 0.0) return std::nullopt;
  result.point =
      eigen.eigenvectors() * (eigen.eigenvectors().transpose() * b).cwiseQuotient(lambda);
  if (!RayDistances(rays, options, &result)) return std::nullopt;
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
    // Each ray's sigma in metres at the point: its pixels' at the range found last. The rays'
    // conditioning does not depend on the weights: checked once, above.
    std::vector<double> weights(rays.size());
    for (int pass = 0; pass < options.reweightings; ++pass) {
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const Camera& camera = cameras[observations[i].camera];
        const double range = (result->point - rays[i].origin).dot(rays[i].direction);
        const double px = std::hypot(options.pixel_sigma, observations[i].sigma_px);
        const double across = px * range / (0.5 * (camera.fx + camera.fy));
        weights[i] = 1.0 / (across * across + options.ray_sigma_m * options.ray_sigma_m);
      }
      result->point = WeightedPoint(rays, weights);
      if (!RayDistances(rays, options, &*result)) return std::nullopt;
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
