// A pinhole camera with OpenCV's 5-coefficient distortion (k1 k2 p1 p2 k3) and its pose
// cam_from_world. Frames (DESIGN.md): world metres, z up; camera x right, y down, z forward;
// pixels with centres at integer coordinates (OpenCV).
//
// "Normalized" coordinates are (X/Z, Y/Z) of a point in the camera frame before distortion;
// "ideal pixels" are K applied to normalized coordinates (no distortion).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "p4/geometry/camera_clock.h"
#include "p4/geometry/pose.h"

namespace p4 {

struct Camera {
  std::string name;
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  std::array<double, 5> distortion{};  // k1 k2 p1 p2 k3 (OpenCV order)
  Rigid3d cam_from_world;
  CameraClock clock;  // when its frames were exposed, in the rig's time (camera_clock.h)

  Eigen::Matrix3d K() const;
  bool HasDistortion() const;

  // Optical centre in the world frame.
  Eigen::Vector3d Center() const;

  // Applies / removes the lens distortion on normalized coordinates. Undistort iterates (as
  // cv::undistortPoints does) and is exact to ~1e-12 within the image for moderate distortion.
  Eigen::Vector2d Distort(const Eigen::Vector2d& normalized) const;
  Eigen::Vector2d Undistort(const Eigen::Vector2d& distorted_normalized) const;

  Eigen::Vector2d PixelFromNormalized(const Eigen::Vector2d& normalized) const;  // distorts
  Eigen::Vector2d NormalizedFromPixel(const Eigen::Vector2d& pixel) const;       // undistorts
  Eigen::Vector2d IdealPixelFromNormalized(const Eigen::Vector2d& normalized) const;

  // Pixel of a world point; nullopt when the point is not in front of the camera (z <= 1 mm).
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& point_in_world) const;

  // Unit direction, in the world frame, of the ray through a pixel (starts at Center()).
  Eigen::Vector3d RayDirection(const Eigen::Vector2d& pixel) const;

  // Inside the image with a margin in pixels (the pixel-centre convention: [-0.5, w-0.5)).
  bool InImage(const Eigen::Vector2d& pixel, double margin = 0.0) const;

  // In front of the camera and projecting inside the image.
  bool Sees(const Eigen::Vector3d& point_in_world, double margin = 0.0) const;
};

// Checks that the camera can be used: positive size and focal lengths, finite numbers, a proper
// rotation (orthonormal, det +1, to 1e-6). On failure writes the field that is wrong to *error.
bool ValidateCamera(const Camera& camera, std::string* error);

}  // namespace p4
