// Building camera poses by where they stand and what they look at (simulator, tests, UI).
#pragma once

#include <Eigen/Core>

#include "p4/geometry/pose.h"

namespace p4 {

// cam_from_world of a camera at `eye` (world) whose optical axis points at `target`, with the
// image's "up" (-y of the camera) as close to `up` as possible. Precondition: target != eye and
// the viewing direction is not parallel to `up`.
Rigid3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
               const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

}  // namespace p4
