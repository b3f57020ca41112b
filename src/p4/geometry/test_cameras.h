// Cameras for the geometry tests: a club-like rig looking at the table.
#pragma once

#include <vector>

#include "p4/geometry/camera.h"
#include "p4/geometry/look_at.h"

namespace p4::testing {

inline Camera MakeCamera(const std::string& name, const Eigen::Vector3d& eye,
                         const Eigen::Vector3d& target = Eigen::Vector3d::Zero(),
                         std::array<double, 5> distortion = {}) {
  Camera camera;
  camera.name = name;
  camera.width = 1280;
  camera.height = 720;
  camera.fx = 1000.0;
  camera.fy = 1002.0;
  camera.cx = 641.5;
  camera.cy = 359.0;
  camera.distortion = distortion;
  camera.cam_from_world = LookAt(eye, target);
  return camera;
}

inline std::vector<Camera> ClubCameras() {
  return {
      MakeCamera("side", {0.2, -3.5, 1.5}),
      MakeCamera("end_a", {-4.0, -0.8, 2.0}, {0.3, 0.0, 0.0}, {-0.12, 0.05, 0.001, -0.0005, 0.0}),
      MakeCamera("end_b", {4.0, 0.8, 2.0}), MakeCamera("other_side", {-0.5, 3.4, 1.6})};
}

}  // namespace p4::testing
