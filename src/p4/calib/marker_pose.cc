#include "p4/calib/marker_pose.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/aruco.hpp>

#include "p4/calib/aruco_markers.h"
#include "p4/core/robust.h"

namespace p4::calib {
namespace {

double Bilinear(const cv::Mat& gray, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](int xx, int yy) {
    return static_cast<double>(
        gray.at<uint8_t>(std::clamp(yy, 0, gray.rows - 1), std::clamp(xx, 0, gray.cols - 1)));
  };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

// A line through `point` along `direction` (unit).
struct Line {
  Eigen::Vector2d point, direction;
};

// The marker's outer edge on one side, from sub-pixel edge points across it.
std::optional<Line> FitEdge(const cv::Mat& gray, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            const Eigen::Vector2d& centre) {
  const Eigen::Vector2d along = (b - a).normalized();
  Eigen::Vector2d normal(-along.y(), along.x());
  if (normal.dot(0.5 * (a + b) - centre) < 0.0) normal = -normal;  // outwards
  // Half a module of the border each side of the edge: the black border inside, the white quiet
  // zone outside, nothing else.
  const double inset = std::abs(normal.dot(0.5 * (a + b) - centre));  // centre to this side
  const double reach = std::clamp(0.5 * inset / 3.0, 0.75, 4.0);
  const double length = (b - a).norm();
  std::vector<Eigen::Vector2d> points;
  for (double t = 0.15 * length; t <= 0.85 * length; t += 0.5) {
    const Eigen::Vector2d p = a + t * along;
    // Gradient along the normal, sampled every 0.25 px; its centroid is the edge.
    double sw = 0.0, ss = 0.0,
           prev = Bilinear(gray, p.x() - reach * normal.x(), p.y() - reach * normal.y());
    for (double s = -reach + 0.25; s <= reach + 1e-9; s += 0.25) {
      const Eigen::Vector2d q = p + s * normal;
      const double v = Bilinear(gray, q.x(), q.y());
      const double g = v - prev;  // dark inside to bright outside: positive
      prev = v;
      if (g > 0.0) sw += g, ss += g * (s - 0.125);
    }
    if (sw < 20.0) continue;  // no clear edge here (occluded, shadow)
    points.push_back(p + (ss / sw) * normal);
  }
  if (points.size() < 4) return std::nullopt;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : points) mean += p;
    mean /= points.size();
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
    const Line line{mean, eig.eigenvectors().col(1)};
    if (pass == 1) return line;
    const Eigen::Vector2d n(-line.direction.y(), line.direction.x());
    std::erase_if(points,
                  [&](const Eigen::Vector2d& p) { return std::abs(n.dot(p - mean)) > 0.5; });
    if (points.size() < 4) return std::nullopt;
  }
  return std::nullopt;
}

std::optional<Eigen::Vector2d> Intersect(const Line& l1, const Line& l2) {
  Eigen::Matrix2d m;
  m << l1.direction, -l2.direction;
  if (std::abs(m.determinant()) < 1e-3) return std::nullopt;
  const Eigen::Vector2d st = m.colPivHouseholderQr().solve(l2.point - l1.point);
  return l1.point + st(0) * l1.direction;
}

}  // namespace

void RefineMarkerCorners(const cv::Mat& gray, std::array<Eigen::Vector2d, 4>* corners) {
  for (int iteration = 0; iteration < 2; ++iteration) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& c : *corners) centre += 0.25 * c;
    std::array<std::optional<Line>, 4> edges;
    for (int k = 0; k < 4; ++k) {
      edges[k] = FitEdge(gray, (*corners)[k], (*corners)[(k + 1) % 4], centre);
    }
    std::array<Eigen::Vector2d, 4> refined = *corners;
    for (int k = 0; k < 4; ++k) {
      // Corner k joins edge k-1 (from corner k-1) and edge k (to corner k+1).
      const auto& before = edges[(k + 3) % 4];
      const auto& after = edges[k];
      if (!before || !after) continue;
      const auto p = Intersect(*before, *after);
      if (p && (*p - (*corners)[k]).norm() < 3.0) refined[k] = *p;
    }
    *corners = refined;
  }
}

std::vector<MarkerObservation> DetectMarkers(const cv::Mat& gray, const std::string& dictionary) {
  const auto dict = cv::aruco::getPredefinedDictionary(ArucoDictionaryId(dictionary));
  auto parameters = cv::aruco::DetectorParameters::create();
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(gray, dict, corners, ids, parameters);
  std::vector<MarkerObservation> out;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    MarkerObservation m;
    m.id = ids[i];
    for (int k = 0; k < 4; ++k) m.corners[k] = {corners[i][k].x, corners[i][k].y};
    RefineMarkerCorners(gray, &m.corners);
    out.push_back(m);
  }
  return out;
}

std::vector<MarkerObservation> AverageObservations(
    const std::vector<std::vector<MarkerObservation>>& frames) {
  std::map<int, std::pair<MarkerObservation, int>> sums;
  for (const auto& frame : frames) {
    for (const MarkerObservation& m : frame) {
      auto& [sum, count] = sums[m.id];
      if (count == 0) {
        sum = m;
      } else {
        for (int k = 0; k < 4; ++k) sum.corners[k] += m.corners[k];
      }
      ++count;
    }
  }
  std::vector<MarkerObservation> out;
  for (auto& [id, entry] : sums) {
    auto& [sum, count] = entry;
    if (2 * count < static_cast<int>(frames.size())) continue;
    for (int k = 0; k < 4; ++k) sum.corners[k] /= count;
    out.push_back(sum);
  }
  return out;
}

std::optional<MarkerPoseResult> SolveMarkerPose(const std::optional<Camera>& intrinsics,
                                                const std::string& name, int width, int height,
                                                const std::vector<MarkerObservation>& observed,
                                                const MarkerLayout& layout, int min_markers,
                                                std::string* error) {
  MarkerPoseResult result;
  std::vector<PointMatch> points;
  for (const MarkerObservation& m : observed) {
    const auto it = layout.corners.find(m.id);
    if (it == layout.corners.end()) {
      result.unknown.push_back(m.id);
      continue;
    }
    result.used.push_back(m.id);
    for (int k = 0; k < 4; ++k) points.push_back({m.corners[k], it->second[k]});
  }
  if (static_cast<int>(result.used.size()) < min_markers) {
    *error = "sees " + std::to_string(result.used.size()) + " marker(s) of the layout, " +
             std::to_string(min_markers) + " needed";
    if (!result.unknown.empty()) {
      *error += " (found ids not in the layout:";
      for (int id : result.unknown) {
        *error += ' ';
        *error += std::to_string(id);
      }
      *error += ")";
    }
    return std::nullopt;
  }
  const auto solve = [&](const std::vector<PointMatch>& p) {
    if (!intrinsics) return SolvePoseAndFocal(name, width, height, p, error);
    Camera camera = *intrinsics;
    camera.name = name;
    return SolvePose(camera, p, error);
  };
  std::optional<PoseFit> fit = solve(points);
  if (!fit) return std::nullopt;
  // A marker that fits far worse than the others (half hidden, mis-refined) is left out once.
  const int n = static_cast<int>(result.used.size());
  if (n > min_markers && n > 1) {
    std::vector<double> marker_rms(n);
    for (int i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += fit->errors_px[4 * i + k] * fit->errors_px[4 * i + k];
      marker_rms[i] = std::sqrt(sum / 4.0);
    }
    const double limit = std::max(1.0, 3.0 * Median(marker_rms));
    std::vector<PointMatch> kept;
    std::vector<int> kept_ids;
    for (int i = 0; i < n; ++i) {
      if (marker_rms[i] > limit) {
        result.dropped.push_back(result.used[i]);
        continue;
      }
      kept_ids.push_back(result.used[i]);
      kept.insert(kept.end(), points.begin() + 4 * i, points.begin() + 4 * i + 4);
    }
    if (!result.dropped.empty() && static_cast<int>(kept_ids.size()) >= min_markers) {
      if (auto refit = solve(kept)) {
        fit = std::move(refit);
        result.used = kept_ids;
      } else {
        result.dropped.clear();
      }
    } else {
      result.dropped.clear();
    }
  }
  result.fit = std::move(*fit);
  return result;
}

}  // namespace p4::calib
