#include "p4/io/calib_files.h"

#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "p4/core/error.h"
#include "p4/io/csv.h"
#include "p4/io/video_reader.h"
#include "p4/io/yaml_file.h"

namespace p4 {
namespace {

bool IsImageFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".bmp" || ext == ".tif" ||
         ext == ".tiff" || ext == ".pgm" || ext == ".ppm";
}

GrayFrame ReadImage(const std::filesystem::path& p) {
  cv::Mat gray = cv::imread(p.string(), cv::IMREAD_GRAYSCALE);
  if (gray.empty()) throw Error(p.string() + ": cannot read the image");
  return {p.filename().string(), gray};
}

calib::MarkerLayout ParseMarkerLayout(const std::string& path) {
  const YAML::Node root = LoadYamlMap(path);
  const YAML::Node list = YamlList(path, root, "markers");
  calib::MarkerLayout layout;
  if (root["dictionary"].IsDefined()) {
    if (!root["dictionary"].IsScalar()) throw Error(path + ": 'dictionary' must be a name");
    layout.dictionary = root["dictionary"].Scalar();
  }
  int index = 0;
  for (const YAML::Node& node : list) {
    const std::string where = fmt::format("{}: marker {}", path, index++);
    int id = 0;
    if (!node.IsMap() || !YamlInt(node["id"], &id)) throw Error(where + ": missing integer 'id'");
    const YAML::Node corners = node["corners"];
    if (!corners.IsDefined())
      throw Error(where + " (id " + std::to_string(id) + "): missing 'corners'");
    // An opencv-matrix ({rows, cols, data}) or a list of points (or of numbers).
    std::vector<double> values;
    int rows = 0, cols = 0;
    std::string why;
    if (!YamlMatrix(corners, &values, &rows, &cols, &why)) {
      throw Error(fmt::format("{}: 'corners': {}", where, why));
    }
    if (values.size() != 12) {
      throw Error(fmt::format("{} (id {}): 'corners' must be 4 points x,y,z, got {} numbers", where,
                              id, values.size()));
    }
    if (layout.corners.count(id)) throw Error(fmt::format("{}: id {} appears twice", where, id));
    auto& quad = layout.corners[id];
    for (int k = 0; k < 4; ++k) {
      quad[k] = {values[3 * k], values[3 * k + 1], values[3 * k + 2]};
      if (!quad[k].allFinite()) throw Error(where + ": 'corners' has a non-finite number");
    }
  }
  if (layout.corners.empty()) throw Error(path + ": the 'markers' list is empty");
  return layout;
}
}  // namespace

calib::MarkerLayout ReadMarkerLayout(const std::string& path) {
  return ReadYamlFile(path, [&] { return ParseMarkerLayout(path); });
}

std::vector<calib::PointMatch> ReadPointMatches(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(path + ": no such file");
  const auto rows = ReadCsv(path, "u,v,x,y,z");
  std::vector<calib::PointMatch> points;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    calib::PointMatch p;
    p.pixel = {CsvNumber(path, i, rows[i][0]), CsvNumber(path, i, rows[i][1])};
    p.world = {CsvNumber(path, i, rows[i][2]), CsvNumber(path, i, rows[i][3]),
               CsvNumber(path, i, rows[i][4])};
    points.push_back(p);
  }
  if (points.empty()) throw Error(path + ": no points after the header");
  return points;
}

std::vector<GrayFrame> ReadGrayFrames(const std::string& path, int max_frames, int video_step) {
  namespace fs = std::filesystem;
  std::vector<GrayFrame> frames;
  const fs::path p(path);
  const std::string pattern = p.filename().string();
  const bool glob = pattern.find_first_of("*?[") != std::string::npos;
  if (fs::is_directory(path) || glob) {
    const fs::path dir = glob ? (p.has_parent_path() ? p.parent_path() : fs::path(".")) : p;
    if (!fs::is_directory(dir)) throw Error(dir.string() + ": no such folder");
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (!entry.is_regular_file() || !IsImageFile(entry.path())) continue;
      if (glob && fnmatch(pattern.c_str(), entry.path().filename().c_str(), 0) != 0) continue;
      files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
      throw Error(path + (glob ? ": no image file matches"
                               : ": no image files (.jpg, .png, ...) in the folder"));
    }
    for (const auto& f : files) {
      if (static_cast<int>(frames.size()) >= max_frames) break;
      frames.push_back(ReadImage(f));
    }
    return frames;
  }
  if (!VideoReader::IsLive(path) && !fs::exists(path)) throw Error(path + ": no such file");
  if (IsImageFile(path)) return {ReadImage(path)};
  VideoReader reader(path);
  I420Image frame;
  TimeNs pts = 0;
  const int step = std::max(1, video_step);
  for (int index = 0; static_cast<int>(frames.size()) < max_frames && reader.Read(&frame, &pts);
       ++index) {
    if (index % step != 0) continue;
    const cv::Mat y(frame.height(), frame.width(), CV_8UC1, frame.y());
    frames.push_back({"frame " + std::to_string(index), y.clone()});
  }
  if (frames.empty()) throw Error(path + ": the video has no frames");
  return frames;
}

}  // namespace p4
