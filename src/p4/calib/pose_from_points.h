// A camera's pose (and, if unknown, its focal length) from image points of known world points:
// the core of `calibrate rig` (marker corners, paper §2) and `calibrate table` (table corners and
// net-post tops). OpenCV calib3d does the solving; this file adds the checks a user needs.
//
// Frames: world metres (DESIGN.md), pixels in the distorted image (OpenCV convention).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/geometry/camera.h"

namespace p4::calib {

struct PointMatch {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector3d world = Eigen::Vector3d::Zero();
};

struct PoseFit {
  Camera camera;                  // the input intrinsics (or the estimated ones) with the pose
  double rms_px = 0.0;            // reprojection error over the points
  double max_px = 0.0;            // the worst point's
  std::vector<double> errors_px;  // per point, in the input order
};

// Why a set of points cannot give a pose, or "" when it can: fewer than `min_points`, world
// points (nearly) on one line, or image points (nearly) on one pixel.
std::string CheckPointSpread(std::span<const PointMatch> points, int min_points);

// Pose of a camera with known intrinsics (`intrinsics`: size, K, distortion; its pose is
// ignored): SQPnP, then Levenberg-Marquardt over all points. nullopt with *error set when the
// points are too few or degenerate or the solution puts points behind the camera.
std::optional<PoseFit> SolvePose(const Camera& intrinsics, std::span<const PointMatch> points,
                                 std::string* error);

struct FocalSearchOptions {
  // Focal lengths tried, as multiples of the image's larger side (phones and webcams lie well
  // inside: 0.5-1.5; telephoto lenses above).
  double min_focal = 0.3;
  double max_focal = 6.0;
  int steps = 80;
};

// Pose and focal length (fx = fy, principal point at the image centre, no distortion) of a camera
// whose intrinsics are unknown, from >= 4 points (paper §5's "calibration from the table"):
// the focal length that reprojects best over a geometric scan seeds a joint refinement of focal
// length and pose (cv::calibrateCamera with those parameters fixed).
std::optional<PoseFit> SolvePoseAndFocal(const std::string& name, int width, int height,
                                         std::span<const PointMatch> points, std::string* error,
                                         const FocalSearchOptions& options = {});

// Reprojection errors (pixels) of points through a camera; infinity for a point behind it.
std::vector<double> ReprojectionErrors(const Camera& camera, std::span<const PointMatch> points);

}  // namespace p4::calib
