// Conversions between P4's Camera / Rigid3d and OpenCV's calib3d conventions (K, distortion
// k1 k2 p1 p2 k3, rvec/tvec of cam_from_world). Both use the same camera frame (x right, y down,
// z forward) and pixel-centre convention, so these are copies, not changes of frame.
#pragma once

#include <opencv2/core.hpp>

#include "p4/geometry/camera.h"
#include "p4/geometry/pose.h"

namespace p4::calib {

cv::Matx33d CameraMatrix(const Camera& camera);
cv::Mat DistortionCoefficients(const Camera& camera);  // 1x5 CV_64F
// Sets fx, fy, cx, cy and the distortion of *camera from OpenCV's matrices (4-14 coefficients;
// beyond the 5th they must be zero).
void SetIntrinsics(const cv::Mat& K, const cv::Mat& distortion, Camera* camera);

Rigid3d RigidFromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec);
void RvecTvecFromRigid(const Rigid3d& pose, cv::Mat* rvec, cv::Mat* tvec);

}  // namespace p4::calib
