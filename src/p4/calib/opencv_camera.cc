#include "p4/calib/opencv_camera.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "p4/core/error.h"

namespace p4::calib {

cv::Matx33d CameraMatrix(const Camera& camera) {
  return {camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0};
}

cv::Mat DistortionCoefficients(const Camera& camera) {
  cv::Mat d(1, 5, CV_64F);
  for (int i = 0; i < 5; ++i) d.at<double>(i) = camera.distortion[i];
  return d;
}

void SetIntrinsics(const cv::Mat& K, const cv::Mat& distortion, Camera* camera) {
  cv::Mat k, d;
  K.convertTo(k, CV_64F);
  distortion.reshape(1, 1).convertTo(d, CV_64F);
  camera->fx = k.at<double>(0, 0);
  camera->fy = k.at<double>(1, 1);
  camera->cx = k.at<double>(0, 2);
  camera->cy = k.at<double>(1, 2);
  camera->distortion.fill(0.0);
  for (int i = 0; i < d.cols; ++i) {
    if (i < 5) {
      camera->distortion[i] = d.at<double>(i);
    } else if (d.at<double>(i) != 0.0) {
      throw Error("distortion coefficient " + std::to_string(i + 1) +
                  " is not zero: P4 uses OpenCV's 5-coefficient model");
    }
  }
}

Rigid3d RigidFromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat r;
  cv::Rodrigues(rvec, r);
  Rigid3d pose;
  cv::Mat r64, t64;
  r.convertTo(r64, CV_64F);
  tvec.reshape(1, 3).convertTo(t64, CV_64F);
  cv::cv2eigen(r64, pose.rotation);
  cv::cv2eigen(t64, pose.translation);
  return pose;
}

void RvecTvecFromRigid(const Rigid3d& pose, cv::Mat* rvec, cv::Mat* tvec) {
  cv::Mat r;
  cv::eigen2cv(pose.rotation, r);
  cv::Rodrigues(r, *rvec);
  cv::eigen2cv(pose.translation, *tvec);
  *tvec = tvec->clone();
}

}  // namespace p4::calib
