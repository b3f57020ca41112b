#include "p4/calib/pose_from_points.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>

#include "p4/calib/opencv_camera.h"

namespace p4::calib {
namespace {

void ToOpenCv(std::span<const PointMatch> points, std::vector<cv::Point3d>* world,
              std::vector<cv::Point2d>* pixels) {
  world->clear();
  pixels->clear();
  for (const PointMatch& p : points) {
    world->emplace_back(p.world.x(), p.world.y(), p.world.z());
    pixels->emplace_back(p.pixel.x(), p.pixel.y());
  }
}

double Rms(const std::vector<double>& errors) {
  double sum = 0.0;
  for (double e : errors) sum += e * e;
  return errors.empty() ? 0.0 : std::sqrt(sum / errors.size());
}

PoseFit MakeFit(const Camera& camera, std::span<const PointMatch> points) {
  PoseFit fit;
  fit.camera = camera;
  fit.errors_px = ReprojectionErrors(camera, points);
  fit.rms_px = Rms(fit.errors_px);
  fit.max_px = *std::max_element(fit.errors_px.begin(), fit.errors_px.end());
  return fit;
}

}  // namespace

std::string CheckPointSpread(std::span<const PointMatch> points, int min_points) {
  if (static_cast<int>(points.size()) < min_points) {
    return std::to_string(points.size()) + " point(s), at least " + std::to_string(min_points) +
           " needed";
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector2d mean_px = Eigen::Vector2d::Zero();
  for (const PointMatch& p : points) mean += p.world, mean_px += p.pixel;
  mean /= points.size();
  mean_px /= points.size();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  double spread_px = 0.0;
  for (const PointMatch& p : points) {
    scatter += (p.world - mean) * (p.world - mean).transpose();
    spread_px = std::max(spread_px, (p.pixel - mean_px).norm());
  }
  // Eigenvalues ascending: the middle one is the spread across the best line.
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvalues();
  if (ev(2) <= 0.0 || ev(1) < 1e-6 * ev(2)) return "the world points lie on one line";
  if (spread_px < 2.0) return "the image points are all at one place";
  return "";
}

std::vector<double> ReprojectionErrors(const Camera& camera, std::span<const PointMatch> points) {
  std::vector<double> errors;
  errors.reserve(points.size());
  for (const PointMatch& p : points) {
    const auto px = camera.Project(p.world);
    errors.push_back(px ? (*px - p.pixel).norm() : std::numeric_limits<double>::infinity());
  }
  return errors;
}

std::optional<PoseFit> SolvePose(const Camera& intrinsics, std::span<const PointMatch> points,
                                 std::string* error) {
  if (const std::string why = CheckPointSpread(points, 4); !why.empty()) {
    *error = why;
    return std::nullopt;
  }
  std::vector<cv::Point3d> world;
  std::vector<cv::Point2d> pixels;
  ToOpenCv(points, &world, &pixels);
  const cv::Mat K(CameraMatrix(intrinsics));
  const cv::Mat dist = DistortionCoefficients(intrinsics);
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(world, pixels, K, dist, rvec, tvec, false, cv::SOLVEPNP_SQPNP)) {
    *error = "no pose fits the points";
    return std::nullopt;
  }
  cv::solvePnPRefineLM(world, pixels, K, dist, rvec, tvec);
  Camera camera = intrinsics;
  camera.cam_from_world = RigidFromRvecTvec(rvec, tvec);
  PoseFit fit = MakeFit(camera, points);
  if (!std::isfinite(fit.max_px)) {
    *error = "the best pose puts points behind the camera";
    return std::nullopt;
  }
  return fit;
}

std::optional<PoseFit> SolvePoseAndFocal(const std::string& name, int width, int height,
                                         std::span<const PointMatch> points, std::string* error,
                                         const FocalSearchOptions& options) {
  if (width <= 0 || height <= 0) {
    *error = "the image size is unknown";
    return std::nullopt;
  }
  Camera guess;
  guess.name = name;
  guess.width = width;
  guess.height = height;
  guess.cx = 0.5 * (width - 1);
  guess.cy = 0.5 * (height - 1);
  const double side = std::max(width, height);
  std::optional<PoseFit> best;
  for (int i = 0; i <= options.steps; ++i) {
    const double f = side * options.min_focal *
                     std::pow(options.max_focal / options.min_focal,
                              static_cast<double>(i) / std::max(1, options.steps));
    guess.fx = guess.fy = f;
    std::string why;
    auto fit = SolvePose(guess, points, &why);
    if (!fit) {
      if (!why.empty() && why.find("behind") == std::string::npos) {
        *error = why;  // too few or degenerate points: no focal length will do
        return std::nullopt;
      }
      continue;
    }
    if (!best || fit->rms_px < best->rms_px) best = std::move(fit);
  }
  if (!best) {
    *error = "no focal length in the searched range puts the points in front of the camera";
    return std::nullopt;
  }
  // Joint refinement of the focal length and the pose.
  std::vector<cv::Point3f> world;
  std::vector<cv::Point2f> pixels;
  for (const PointMatch& p : points) {
    world.emplace_back(p.world.x(), p.world.y(), p.world.z());
    pixels.emplace_back(p.pixel.x(), p.pixel.y());
  }
  cv::Mat K(CameraMatrix(best->camera)), dist = cv::Mat::zeros(1, 5, CV_64F);
  cv::Mat rvec, tvec;
  RvecTvecFromRigid(best->camera.cam_from_world, &rvec, &tvec);
  std::vector<cv::Mat> rvecs{rvec}, tvecs{tvec};
  const int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_PRINCIPAL_POINT |
                    cv::CALIB_FIX_ASPECT_RATIO | cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K1 |
                    cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3;
  try {
    cv::calibrateCamera(std::vector<std::vector<cv::Point3f>>{world},
                        std::vector<std::vector<cv::Point2f>>{pixels}, cv::Size(width, height), K,
                        dist, rvecs, tvecs, flags);
  } catch (const cv::Exception&) {
    return best;  // the scan's answer stands
  }
  Camera refined = best->camera;
  SetIntrinsics(K, dist, &refined);
  refined.cam_from_world = RigidFromRvecTvec(rvecs[0], tvecs[0]);
  PoseFit fit = MakeFit(refined, points);
  if (!(fit.rms_px <= best->rms_px) || !(refined.fx > 0.0)) return best;
  return fit;
}

}  // namespace p4::calib
