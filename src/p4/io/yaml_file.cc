#include "p4/io/yaml_file.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace p4 {

YAML::Node LoadYamlMap(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(path + ": no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  if (text.empty()) throw Error(path + ": the file is empty");
  // OpenCV's header line is no YAML directive ("%YAML 1.x" is): blanked, lines keep their numbers.
  if (text.rfind("%YAML:", 0) == 0) text.replace(0, text.find('\n'), "");
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw Error(
        fmt::format("{}: line {}: cannot parse the file ({})", path, e.mark.line + 1, e.msg));
  } catch (const YAML::Exception& e) {
    throw Error(path + ": cannot parse the file (" + e.what() + ")");
  }
  if (!root.IsMap()) throw Error(path + ": expected a map of keys (e.g. 'cameras:')");
  return root;
}

YAML::Node YamlList(const std::string& path, const YAML::Node& root, const char* key) {
  const YAML::Node list = root[key];
  if (!list.IsDefined() || !list.IsSequence()) throw Error(path + ": missing '" + key + "' list");
  return list;
}

bool YamlNumber(const YAML::Node& node, double* value) {
  if (!node.IsDefined() || !node.IsScalar()) return false;
  return YAML::convert<double>::decode(node, *value);
}

bool YamlInt(const YAML::Node& node, int* value) {
  if (!node.IsDefined() || !node.IsScalar()) return false;
  return YAML::convert<int>::decode(node, *value);
}

}  // namespace p4
