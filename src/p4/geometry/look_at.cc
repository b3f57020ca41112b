#include "p4/geometry/look_at.h"

namespace p4 {

Rigid3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
               const Eigen::Vector3d& up) {
  const Eigen::Vector3d z = (target - eye).normalized();  // forward
  const Eigen::Vector3d x = z.cross(up).normalized();     // right
  const Eigen::Vector3d y = z.cross(x);                   // down
  Rigid3d cam_from_world;
  cam_from_world.rotation.row(0) = x.transpose();
  cam_from_world.rotation.row(1) = y.transpose();
  cam_from_world.rotation.row(2) = z.transpose();
  cam_from_world.translation = -(cam_from_world.rotation * eye);
  return cam_from_world;
}

}  // namespace p4
