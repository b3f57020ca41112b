#include "p4/calib/intrinsics.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "p4/calib/opencv_camera.h"
#include "p4/core/robust.h"

namespace p4::calib {
namespace {

struct Pass {
  cv::Mat K, dist, std_intrinsics;
  std::vector<double> view_rms;
  double rms = 0.0;
};

Pass Calibrate(std::span<const BoardView> views, const std::vector<int>& use, cv::Size size,
               const IntrinsicsOptions& options) {
  std::vector<std::vector<cv::Point3f>> board;
  std::vector<std::vector<cv::Point2f>> pixels;
  for (int i : use) {
    board.push_back(views[i].board);
    pixels.push_back(views[i].pixels);
  }
  int flags = 0;
  if (options.fix_aspect_ratio) flags |= cv::CALIB_FIX_ASPECT_RATIO;
  if (options.zero_tangential) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  if (options.fix_k3) flags |= cv::CALIB_FIX_K3;
  Pass pass;
  pass.K = cv::Mat::eye(3, 3, CV_64F);  // fx / fy = 1 for CALIB_FIX_ASPECT_RATIO
  pass.dist = cv::Mat::zeros(1, 5, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat std_extrinsics, per_view;
  pass.rms = cv::calibrateCamera(board, pixels, size, pass.K, pass.dist, rvecs, tvecs,
                                 pass.std_intrinsics, std_extrinsics, per_view, flags);
  for (int i = 0; i < per_view.rows; ++i) pass.view_rms.push_back(per_view.at<double>(i));
  return pass;
}

}  // namespace

bool IntrinsicsOptions::IsValid(std::string* error) const {
  if (min_views < 3) {
    *error = "min_views must be at least 3, got " + std::to_string(min_views);
    return false;
  }
  if (!(outlier_factor > 1.0) || !(outlier_min_px >= 0.0)) {
    *error = "outlier_factor must be > 1 and outlier_min_px >= 0";
    return false;
  }
  return true;
}

std::optional<IntrinsicsResult> CalibrateIntrinsics(std::span<const BoardView> views, int width,
                                                    int height, const std::string& name,
                                                    const IntrinsicsOptions& options,
                                                    std::string* error) {
  if (!options.IsValid(error)) return std::nullopt;
  if (static_cast<int>(views.size()) < options.min_views) {
    *error = "the board was found in " + std::to_string(views.size()) + " image(s), at least " +
             std::to_string(options.min_views) + " needed (tilt the board differently in each)";
    return std::nullopt;
  }
  const cv::Size size(width, height);
  std::vector<int> use(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) use[i] = static_cast<int>(i);
  IntrinsicsResult result;
  Pass pass;
  try {
    pass = Calibrate(views, use, size, options);
    const double limit =
        std::max(options.outlier_min_px, options.outlier_factor * Median(pass.view_rms));
    std::vector<int> kept;
    for (std::size_t k = 0; k < use.size(); ++k) {
      if (pass.view_rms[k] > limit) {
        result.dropped.push_back(use[k]);
        result.dropped_rms_px.push_back(pass.view_rms[k]);
      } else {
        kept.push_back(use[k]);
      }
    }
    if (!result.dropped.empty() && static_cast<int>(kept.size()) >= options.min_views) {
      use = kept;
      pass = Calibrate(views, use, size, options);
    } else {
      result.dropped.clear();
      result.dropped_rms_px.clear();
    }
  } catch (const cv::Exception& e) {
    *error = std::string("OpenCV could not calibrate: ") + e.what();
    return std::nullopt;
  }
  result.camera.name = name;
  result.camera.width = width;
  result.camera.height = height;
  SetIntrinsics(pass.K, pass.dist, &result.camera);
  result.rms_px = pass.rms;
  result.used = use;
  result.view_rms_px = pass.view_rms;
  const auto sigma = [&](int i) { return pass.std_intrinsics.at<double>(i); };
  result.fx_sigma = sigma(0), result.fy_sigma = sigma(1);
  // With the aspect ratio fixed OpenCV reports the one focal length's spread under fy only.
  if (options.fix_aspect_ratio) result.fx_sigma = result.fy_sigma = std::max(sigma(0), sigma(1));
  result.cx_sigma = sigma(2), result.cy_sigma = sigma(3);
  return result;
}

}  // namespace p4::calib
