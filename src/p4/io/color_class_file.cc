#include "p4/io/color_class_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "p4/core/error.h"
#include "p4/io/yaml_file.h"

namespace p4 {

namespace {
segment::ColorClassSet ParseColorClasses(const std::string& path, const YAML::Node& root) {
  const YAML::Node list = YamlList(path, root, "classes");
  segment::ColorClassSet set;
  int index = 0;
  for (const auto& node : list) {
    const std::string where = fmt::format("{}: classes[{}]", path, index++);
    if (!node.IsMap() || !node["name"].IsDefined() || !node["name"].IsScalar()) {
      throw Error(where + ": missing 'name'");
    }
    segment::ColorClass c;
    c.name = node["name"].Scalar();
    for (const auto& [key, range] :
         {std::pair{"y", &c.y}, std::pair{"u", &c.u}, std::pair{"v", &c.v}}) {
      const YAML::Node bounds = node[key];
      if (!bounds.IsDefined() || !bounds.IsSequence() || bounds.size() != 2) {
        throw Error(fmt::format("{} '{}': '{}' must be [low, high]", where, c.name, key));
      }
      for (int k = 0; k < 2; ++k) {
        int value = 0;
        if (!YamlInt(bounds[k], &value))
          throw Error(fmt::format("{} '{}': {}: not an integer", where, c.name, key));
        if (value < 0 || value > 255) {
          throw Error(fmt::format("{} '{}': {}: {} is outside 0-255", where, c.name, key, value));
        }
        (*range)[k] = static_cast<uint8_t>(value);
      }
    }
    set.classes.push_back(c);
  }
  std::string why;
  if (!set.IsValid(&why)) throw Error(path + ": " + why);
  if (set.MaskOf("ball") == 0) throw Error(path + ": no class named ball* (the ball's classes)");
  return set;
}

std::optional<segment::BallColour> ParseBallLit(const std::string& path, const YAML::Node& root) {
  const YAML::Node lit = root["ball_lit"];
  if (!lit.IsDefined()) return std::nullopt;
  if (!lit.IsSequence() || lit.size() != 3) {
    throw Error(path + ": 'ball_lit' must be [y, u, v] (8-bit levels)");
  }
  double level[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    if (!YamlNumber(lit[k], &level[k]) || !(level[k] >= 0.0 && level[k] <= 255.0)) {
      throw Error(fmt::format("{}: ball_lit[{}]: '{}' is not a level in 0-255", path, k,
                              lit[k].IsScalar() ? lit[k].Scalar() : std::string("?")));
    }
  }
  segment::BallColour ball;
  ball.lit = {static_cast<float>(level[0]), static_cast<float>(level[1]),
              static_cast<float>(level[2])};
  return ball;
}
}  // namespace

ColorClassFile ReadColorClassFile(const std::string& path) {
  return ReadYamlFile(path, [&] {
    const YAML::Node root = LoadYamlMap(path);
    ColorClassFile file;
    file.classes = ParseColorClasses(path, root);
    file.ball = ParseBallLit(path, root);
    return file;
  });
}

segment::ColorClassSet ReadColorClasses(const std::string& path) {
  return ReadColorClassFile(path).classes;
}

void WriteColorClasses(const segment::ColorClassSet& classes, const std::string& path,
                       const segment::BallColour* ball) {
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  if (!fs.isOpened()) throw Error(path + ": cannot create the file");
  fs << "classes"
     << "[";
  for (const auto& c : classes.classes) {
    fs << "{"
       << "name" << c.name;
    fs << "y"
       << "[" << c.y[0] << c.y[1] << "]";
    fs << "u"
       << "[" << c.u[0] << c.u[1] << "]";
    fs << "v"
       << "[" << c.v[0] << c.v[1] << "]"
       << "}";
  }
  fs << "]";
  if (ball) {
    fs << "ball_lit"
       << "[" << ball->lit.y << ball->lit.u << ball->lit.v << "]";
  }
}

}  // namespace p4
