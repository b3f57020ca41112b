// Epipolar geometry between two cameras of a rig (paper §3.4, Figure 9): the ray through a
// pixel of camera i images as a line in camera j; candidates far from it are not the same ball.
//
// Lines are in camera j's *ideal* (undistorted) pixel coordinates, as l = (a, b, c) with
// a u + b v + c = 0 and a^2 + b^2 = 1. Distances undistort the candidate pixel first, so they
// are exact for cameras with lens distortion too.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "p4/geometry/camera.h"

namespace p4 {

// Fundamental matrix mapping ideal pixels of camera i to lines in ideal pixels of camera j.
Eigen::Matrix3d FundamentalMatrix(const Camera& camera_i, const Camera& camera_j);

// Epipolar line in camera j of a (distorted) pixel of camera i, normalised so that a^2+b^2 = 1.
Eigen::Vector3d EpipolarLine(const Camera& camera_i, const Eigen::Vector2d& pixel_i,
                             const Camera& camera_j);

// Distance in pixels of camera j between pixel_j (distorted) and the epipolar line of pixel_i.
double EpipolarDistance(const Camera& camera_i, const Eigen::Vector2d& pixel_i,
                        const Camera& camera_j, const Eigen::Vector2d& pixel_j);

// The epipolar curve of pixel_i drawn in camera j's real (distorted) image: points of the ray
// between depths near_m and far_m projected into camera j, kept where they fall in the image.
std::vector<Eigen::Vector2d> EpipolarCurve(const Camera& camera_i, const Eigen::Vector2d& pixel_i,
                                           const Camera& camera_j, double near_m, double far_m,
                                           int samples = 64);

}  // namespace p4
