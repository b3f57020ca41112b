#include "p4/calib/board.h"

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "p4/calib/aruco_markers.h"
#include "p4/core/error.h"

namespace p4::calib {

bool BoardSpec::IsValid(std::string* error) const {
  const int min_side = type == Type::kChessboard ? 2 : 3;
  if (cols < min_side || rows < min_side) {
    *error = "board size " + std::to_string(cols) + "x" + std::to_string(rows) +
             " is too small (at least " + std::to_string(min_side) + " per side)";
    return false;
  }
  if (!(square > 0.0)) {
    *error = "square size must be positive, got " + std::to_string(square);
    return false;
  }
  if (type == Type::kCharuco) {
    if (!(marker > 0.0 && marker < square)) {
      *error =
          "marker size must be positive and smaller than the square, got " + std::to_string(marker);
      return false;
    }
    try {
      ArucoDictionaryId(dictionary);
    } catch (const Error& e) {
      *error = e.what();
      return false;
    }
  }
  return true;
}

bool DetectBoard(const cv::Mat& gray, const BoardSpec& spec, BoardView* view, std::string* why) {
  view->pixels.clear();
  view->board.clear();
  if (spec.type == BoardSpec::Type::kChessboard) {
    const cv::Size pattern(spec.cols, spec.rows);
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCorners(gray, pattern, corners,
                                   cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
      *why =
          "no " + std::to_string(spec.cols) + "x" + std::to_string(spec.rows) + " chessboard found";
      return false;
    }
    // As OpenCV's calibration sample does: 11x11 window, to 1e-4 px.
    cv::cornerSubPix(gray, corners, cv::Size(11, 11), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 1e-4));
    view->pixels = corners;
    for (int r = 0; r < spec.rows; ++r) {
      for (int c = 0; c < spec.cols; ++c) {
        view->board.emplace_back(static_cast<float>(c * spec.square),
                                 static_cast<float>(r * spec.square), 0.0F);
      }
    }
    return true;
  }
  const auto dictionary = cv::aruco::getPredefinedDictionary(ArucoDictionaryId(spec.dictionary));
  const auto board =
      cv::aruco::CharucoBoard::create(spec.cols, spec.rows, static_cast<float>(spec.square),
                                      static_cast<float>(spec.marker), dictionary);
  std::vector<std::vector<cv::Point2f>> marker_corners;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(gray, dictionary, marker_corners, marker_ids);
  if (marker_ids.empty()) {
    *why = "no " + spec.dictionary + " marker found";
    return false;
  }
  std::vector<cv::Point2f> corners;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, gray, board, corners, ids);
  // Six corners constrain a homography with room to spare; fewer make calibration fragile.
  if (ids.size() < 6) {
    *why = std::to_string(marker_ids.size()) + " marker(s) but only " + std::to_string(ids.size()) +
           " ChArUco corner(s) (6 needed)";
    return false;
  }
  view->pixels = corners;
  for (int id : ids) view->board.push_back(board->chessboardCorners[id]);
  return true;
}

}  // namespace p4::calib
