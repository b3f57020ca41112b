// Intrinsic calibration (K and OpenCV's 5 distortion coefficients) from several views of a board
// (Zhang's method, cv::calibrateCamera), with the views that do not fit dropped and named.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/calib/board.h"
#include "p4/geometry/camera.h"

namespace p4::calib {

struct IntrinsicsOptions {
  bool fix_aspect_ratio = false;  // fx = fy (OpenCV's CALIB_FIX_ASPECT_RATIO with ratio 1)
  bool zero_tangential = false;   // p1 = p2 = 0
  bool fix_k3 = false;            // k3 = 0 (few or central views: k3 is poorly determined)
  int min_views = 4;
  // A view whose reprojection RMS is above outlier_factor x the median and above outlier_min_px
  // is dropped and the calibration repeated once without it (a mis-detected or blurred board).
  double outlier_factor = 3.0;
  double outlier_min_px = 1.0;

  bool IsValid(std::string* error) const;
};

struct IntrinsicsResult {
  Camera camera;  // name, size, K, distortion; identity pose
  double rms_px = 0.0;
  std::vector<int> used;               // indices of the views in the result
  std::vector<double> view_rms_px;     // per used view
  std::vector<int> dropped;            // views dropped as outliers
  std::vector<double> dropped_rms_px;  // their RMS in the first pass
  double fx_sigma = 0.0, fy_sigma = 0.0, cx_sigma = 0.0, cy_sigma = 0.0;  // 1-sigma, pixels
};

// views: the boards found (see DetectBoard); width x height: the images' size. nullopt with
// *error when there are fewer than min_views views or OpenCV fails.
std::optional<IntrinsicsResult> CalibrateIntrinsics(std::span<const BoardView> views, int width,
                                                    int height, const std::string& name,
                                                    const IntrinsicsOptions& options,
                                                    std::string* error);

}  // namespace p4::calib
