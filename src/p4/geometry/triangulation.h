// Triangulation of the ball centre from any number of cameras (paper §3.2, Figure 6): the point
// closest, in the least-squares sense, to all viewing rays.
//
// Frames: rays and points in the world frame, metres; observations in pixels of each camera.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/geometry/camera.h"

namespace p4 {

struct Ray {
  Eigen::Vector3d origin;     // world, metres
  Eigen::Vector3d direction;  // world, unit length
};

struct TriangulationOptions {
  // Smallest accepted ratio of the smallest to the largest eigenvalue of sum(I - d d^T); near
  // zero when all rays are (anti)parallel and depth along them is unknown.
  double min_conditioning = 1e-4;
  // Reject a point that lies behind (or closer than this to) the origin of any ray, metres.
  double min_depth = 0.05;
  // Weights of the views (beyond the paper's plain least squares, which counts every ray's
  // distance alike: the noise of the camera farthest from the ball, whose pixels span the most
  // millimetres there, pulls the point as much as the nearest camera's). With pixel_sigma > 0,
  // TriangulateObservations weighs each ray's distance by 1 / sigma^2, sigma^2 = (px * range /
  // f)^2 + ray_sigma_m^2 with px^2 = pixel_sigma^2 + the view's own sigma_px^2: a view's centre
  // is known to pixel_sigma in its image (more where the view says so: a ball partly hidden),
  // plus ray_sigma_m in the world whatever the range (an error that grows with the object's size
  // in the image). 0: equal weights, as the paper.
  double pixel_sigma = 0.0;  // px
  double ray_sigma_m = 0.0;  // metres
  int reweightings = 2;      // weighted solves after the first (the ranges from the last)

  bool IsValid(std::string* error) const;
};

struct TriangulationResult {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // world, metres
  double rms_ray_distance = 0.0;  // RMS distance from the point to the rays, metres
  double conditioning = 0.0;      // lambda_min / lambda_max of the normal matrix, in [0, 1]
};

// Least-squares point closest to at least two rays (equal weights: the paper's). nullopt for
// fewer than two rays, for (anti)parallel rays (conditioning below the option) or a point
// behind a ray's origin.
std::optional<TriangulationResult> TriangulateRays(std::span<const Ray> rays,
                                                   const TriangulationOptions& options = {});

// One camera's view of the ball.
struct Observation {
  int camera = 0;         // index into the camera list
  Eigen::Vector2d pixel;  // distorted pixel of the ball centre
  double sigma_px = 0.0;  // this view's own centre noise, px, beyond the options' pixel_sigma
                          // (used only when the options weigh the views)
};

struct PointEstimate {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // world, metres
  double mean_reprojection_px = 0.0;                // mean over the observations
  double conditioning = 0.0;
  int num_views = 0;
};

// Triangulates observations of the same point in several cameras (weighted by the options'
// sigmas, see there), and reports the mean reprojection error. Preconditions: observation camera
// indices are valid for `cameras`.
std::optional<PointEstimate> TriangulateObservations(std::span<const Camera> cameras,
                                                     std::span<const Observation> observations,
                                                     const TriangulationOptions& options = {});

// Mean distance in pixels between the observations and the projection of `point`.
double MeanReprojectionError(std::span<const Camera> cameras,
                             std::span<const Observation> observations,
                             const Eigen::Vector3d& point);

}  // namespace p4
