#include "p4/io/rig_file.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "p4/core/error.h"
#include "p4/io/yaml_file.h"

namespace p4 {
namespace {

std::vector<double> ReadMatrix(const YAML::Node& camera, const std::string& key, int want_rows,
                               int want_cols, bool either_orientation, const std::string& where) {
  const YAML::Node node = camera[key];
  if (!node.IsDefined() || node.IsNull()) throw Error(where + ": missing '" + key + "'");
  std::vector<double> values;
  int rows = 0, cols = 0;
  std::string why;
  if (!YamlMatrix(node, &values, &rows, &cols, &why)) throw Error(where + ": " + key + ": " + why);
  const bool size_ok = (rows == want_rows && cols == want_cols) ||
                       (either_orientation && rows == want_cols && cols == want_rows) ||
                       (rows == 1 && cols == want_rows * want_cols);  // flat list
  if (!size_ok) {
    throw Error(where + ": " + key + ": expected a " + std::to_string(want_rows) + "x" +
                std::to_string(want_cols) + " matrix, got " + std::to_string(rows) + "x" +
                std::to_string(cols));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw Error(fmt::format("{}: {}: element {} is not finite", where, key, i));
    }
  }
  return values;
}

int ReadPositiveInt(const YAML::Node& camera, const std::string& key, const std::string& where) {
  const YAML::Node node = camera[key];
  if (!node.IsDefined()) throw Error(where + ": missing '" + key + "'");
  int value = 0;
  if (!YamlInt(node, &value)) throw Error(where + ": " + key + ": expected an integer");
  if (value <= 0)
    throw Error(where + ": " + key + ": must be positive (got " + std::to_string(value) + ")");
  return value;
}

double ReadOptionalNumber(const YAML::Node& camera, const std::string& key, double fallback,
                          const std::string& where) {
  const YAML::Node node = camera[key];
  if (!node.IsDefined()) return fallback;
  double value = 0.0;
  if (!YamlNumber(node, &value)) throw Error(where + ": " + key + ": expected a number");
  if (!std::isfinite(value)) throw Error(where + ": " + key + ": not finite");
  return value;
}

cv::Mat ToMat(const double* data, int rows, int cols) {
  cv::Mat mat(rows, cols, CV_64F);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) mat.at<double>(r, c) = data[r * cols + c];
  }
  return mat;
}

Rig ParseRig(const std::string& path) {
  const YAML::Node root = LoadYamlMap(path);
  const YAML::Node cameras = YamlList(path, root, "cameras");
  Rig rig;
  int index = 0;
  for (const auto& node : cameras) {
    std::string where = path + ": cameras[" + std::to_string(index) + "]";
    if (!node.IsMap()) throw Error(where + ": expected a map of camera fields");
    Camera camera;
    if (!node["name"].IsDefined() || !node["name"].IsScalar()) {
      throw Error(where + ": missing 'name'");
    }
    camera.name = node["name"].Scalar();
    where += " '" + camera.name + "'";
    camera.width = ReadPositiveInt(node, "image_width", where);
    camera.height = ReadPositiveInt(node, "image_height", where);
    const auto k = ReadMatrix(node, "camera_matrix", 3, 3, false, where);
    if (k[1] != 0.0 || k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 || k[8] != 1.0) {
      throw Error(where + ": camera_matrix: expected [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
    }
    camera.fx = k[0];
    camera.cx = k[2];
    camera.fy = k[4];
    camera.cy = k[5];
    if (node["distortion_coefficients"].IsDefined()) {
      const auto d = ReadMatrix(node, "distortion_coefficients", 1, 5, true, where);
      std::copy(d.begin(), d.end(), camera.distortion.begin());
    }
    const auto r = ReadMatrix(node, "rotation", 3, 3, false, where);
    const auto t = ReadMatrix(node, "translation", 3, 1, true, where);
    camera.cam_from_world.rotation =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
    camera.cam_from_world.translation = Eigen::Vector3d(t[0], t[1], t[2]);
    // The clock (optional keys; docs/FORMATS.md): a camera without them is in step.
    camera.clock.has_offset = node["time_offset_s"].IsDefined();
    camera.clock.time_offset_s = ReadOptionalNumber(node, "time_offset_s", 0.0, where);
    camera.clock.clock_rate = ReadOptionalNumber(node, "clock_rate", 1.0, where);
    camera.clock.line_time_s = ReadOptionalNumber(node, "line_time_s", 0.0, where);
    std::string why;
    if (!ValidateCamera(camera, &why)) throw Error(fmt::format("{}: {}", where, why));
    rig.cameras.push_back(camera);
    ++index;
  }
  std::string why;
  if (!ValidateRig(rig, &why)) throw Error(path + ": " + why);
  return rig;
}
}  // namespace

Rig ReadRig(const std::string& path) {
  return ReadYamlFile(path, [&] { return ParseRig(path); });
}

void WriteRig(const Rig& rig, const std::string& path,
              const std::map<std::string, double>& reprojection_error_px) {
  std::string why;
  if (!ValidateRig(rig, &why)) throw Error(path + ": refusing to write an invalid rig: " + why);
  const std::filesystem::path target(path);
  // Keep the extension on the temporary file: FileStorage picks the format from it.
  const std::filesystem::path temporary =
      target.parent_path() / (".tmp-" + target.stem().string() + target.extension().string());
  try {
    cv::FileStorage fs(temporary.string(), cv::FileStorage::WRITE);
    if (!fs.isOpened()) throw Error(path + ": cannot write the file");
    fs << "cameras"
       << "[";
    for (const Camera& camera : rig.cameras) {
      fs << "{";
      fs << "name" << camera.name;
      fs << "image_width" << camera.width << "image_height" << camera.height;
      const Eigen::Matrix3d k = camera.K();
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> k_rm = k;
      fs << "camera_matrix" << ToMat(k_rm.data(), 3, 3);
      fs << "distortion_coefficients" << ToMat(camera.distortion.data(), 1, 5);
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> r = camera.cam_from_world.rotation;
      fs << "rotation" << ToMat(r.data(), 3, 3);
      fs << "translation" << ToMat(camera.cam_from_world.translation.data(), 3, 1);
      // The clock only where it says something (a rig of cameras in step stays as it was).
      if (camera.clock.has_offset || camera.clock.time_offset_s != 0.0) {
        fs << "time_offset_s" << camera.clock.time_offset_s;
      }
      if (camera.clock.clock_rate != 1.0) fs << "clock_rate" << camera.clock.clock_rate;
      if (camera.clock.line_time_s != 0.0) fs << "line_time_s" << camera.clock.line_time_s;
      if (const auto it = reprojection_error_px.find(camera.name);
          it != reprojection_error_px.end()) {
        fs << "reprojection_error_px" << it->second;
      }
      fs << "}";
    }
    fs << "]";
    fs.release();
  } catch (const cv::Exception& e) {
    throw Error(path + ": cannot write the file (" + e.msg + ")");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, target, ec);
  if (ec) throw Error(path + ": cannot write the file (" + ec.message() + ")");
}

}  // namespace p4
