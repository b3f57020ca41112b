#include "p4/calib/aruco_markers.h"

#include <opencv2/aruco.hpp>

#include "p4/core/error.h"

namespace p4 {

int ArucoDictionaryId(const std::string& name) {
  static const std::pair<const char*, int> kNames[] = {
      {"DICT_4X4_50", cv::aruco::DICT_4X4_50}, {"DICT_4X4_100", cv::aruco::DICT_4X4_100},
      {"DICT_5X5_50", cv::aruco::DICT_5X5_50}, {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
      {"DICT_6X6_50", cv::aruco::DICT_6X6_50}, {"DICT_6X6_250", cv::aruco::DICT_6X6_250},
  };
  for (const auto& [n, id] : kNames) {
    if (name == n) return id;
  }
  throw Error("unknown ArUco dictionary '" + name + "' (try DICT_4X4_50)");
}

std::vector<uint8_t> ArucoModules(const std::string& dictionary, int id, int* cells) {
  const auto dict = cv::aruco::getPredefinedDictionary(ArucoDictionaryId(dictionary));
  if (id < 0 || id >= dict->bytesList.rows) {
    throw Error("marker id " + std::to_string(id) + " is not in " + dictionary);
  }
  *cells = dict->markerSize + 2;
  cv::Mat image;
  cv::aruco::drawMarker(dict, id, *cells, image, 1);
  std::vector<uint8_t> black(static_cast<std::size_t>(*cells) * *cells);
  for (int r = 0; r < *cells; ++r) {
    for (int c = 0; c < *cells; ++c) black[r * *cells + c] = image.at<uint8_t>(r, c) < 128 ? 1 : 0;
  }
  return black;
}

}  // namespace p4
