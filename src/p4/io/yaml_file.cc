#include "p4/io/yaml_file.h"

#include <fmt/format.h>

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

bool YamlMatrix(const YAML::Node& node, std::vector<double>* values, int* rows, int* cols,
                std::string* why) {
  values->clear();
  const auto number = [&](const YAML::Node& item) {
    double v = 0.0;
    if (!YamlNumber(item, &v)) return false;
    values->push_back(v);
    return true;
  };
  if (node.IsMap()) {
    const YAML::Node data = node["data"];
    if (!YamlInt(node["rows"], rows) || !YamlInt(node["cols"], cols) || !data.IsSequence()) {
      *why = "expected a matrix with rows, cols and data";
      return false;
    }
    for (const auto& item : data) {
      if (!number(item)) {
        *why = "data holds a value that is not a number";
        return false;
      }
    }
    if (*rows <= 0 || *cols <= 0 ||
        static_cast<int64_t>(values->size()) != static_cast<int64_t>(*rows) * *cols) {
      *why = "data has " + std::to_string(values->size()) + " numbers for a " +
             std::to_string(*rows) + "x" + std::to_string(*cols) + " matrix";
      return false;
    }
    return true;
  }
  if (node.IsSequence()) {
    *rows = 0;
    *cols = -1;
    for (const auto& row : node) {
      if (row.IsSequence()) {
        const int before = static_cast<int>(values->size());
        for (const auto& item : row) {
          if (!number(item)) {
            *why = "holds a value that is not a number";
            return false;
          }
        }
        const int n = static_cast<int>(values->size()) - before;
        if (*cols >= 0 && n != *cols) {
          *why = "rows of different lengths";
          return false;
        }
        *cols = n;
        ++*rows;
      } else if (!number(row)) {
        *why = "holds a value that is not a number";
        return false;
      }
    }
    if (*cols < 0) {  // a flat list
      *rows = 1;
      *cols = static_cast<int>(values->size());
    }
    return true;
  }
  *why = "expected a matrix";
  return false;
}

}  // namespace p4
