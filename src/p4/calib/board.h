// Calibration boards for intrinsics: a chessboard (inner corners) or a ChArUco board (squares,
// markers of an ArUco dictionary), found in grey images with OpenCV (calib3d, aruco contrib).
// Board frame: x along the columns, y along the rows, z = 0 on the board; metres.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace p4::calib {

struct BoardSpec {
  enum class Type { kChessboard, kCharuco };
  Type type = Type::kChessboard;
  // Chessboard: inner corners per row and per column (OpenCV's pattern size, e.g. 9 x 6).
  // ChArUco: squares per row and per column (e.g. 5 x 7).
  int cols = 9;
  int rows = 6;
  double square = 0.025;                   // side of a square, metres
  double marker = 0.0;                     // ChArUco: side of a marker, metres (< square)
  std::string dictionary = "DICT_4X4_50";  // ChArUco only

  // On failure *error names the field and the value.
  bool IsValid(std::string* error) const;
};

struct BoardView {
  std::vector<cv::Point2f> pixels;  // found corners, sub-pixel
  std::vector<cv::Point3f> board;   // the same corners on the board, metres
};

// The board's corners in a grey (CV_8UC1) image. On failure returns false and *why says what was
// missing (no board, too few ChArUco corners).
bool DetectBoard(const cv::Mat& gray, const BoardSpec& spec, BoardView* view, std::string* why);

}  // namespace p4::calib
