// A rigid transform b_from_a: X_b = rotation * X_a + translation (COLMAP's naming). P4 stores a
// camera's pose as cam_from_world (DESIGN.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace p4 {

struct Rigid3d {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const { return rotation * x + translation; }
  Rigid3d Inverse() const {
    Rigid3d inv;
    inv.rotation = rotation.transpose();
    inv.translation = -(inv.rotation * translation);
    return inv;
  }
};

// c_from_a = c_from_b * b_from_a.
inline Rigid3d operator*(const Rigid3d& c_from_b, const Rigid3d& b_from_a) {
  Rigid3d c_from_a;
  c_from_a.rotation = c_from_b.rotation * b_from_a.rotation;
  c_from_a.translation = c_from_b.rotation * b_from_a.translation + c_from_b.translation;
  return c_from_a;
}

}  // namespace p4
