// Reading P4's YAML and JSON inputs (rig, colour classes, marker layout) with yaml-cpp, with P4's
// errors (internal to p4/io). OpenCV's FileStorage writes them (its "%YAML:1.0" first line and
// !!opencv-matrix tags are read here too) but does not read them: its parser loops forever on
// some malformed files (found by fuzz/rig_file_fuzz.cc: "%YAML:1.0\n---  - 2\n-\n").
#pragma once

#include <yaml-cpp/yaml.h>

#include <exception>
#include <string>
#include <vector>

#include "p4/core/error.h"

namespace p4 {

// The file's top-level map. Throws p4::Error naming the file (and the line, for a syntax error)
// for a missing, empty or unparsable file, or one that is not a map.
YAML::Node LoadYamlMap(const std::string& path);

// The top-level list `key` of the file's map. Throws p4::Error naming the file when it is missing.
YAML::Node YamlList(const std::string& path, const YAML::Node& root, const char* key);

// A scalar as a number / an integer: false when it is not one (or not a scalar).
bool YamlNumber(const YAML::Node& node, double* value);
bool YamlInt(const YAML::Node& node, int* value);

// A matrix as numbers, row by row: an opencv-matrix map ({rows, cols, data}, rows x cols numbers)
// or a list of numbers (1 x n) or of rows of numbers (rows of one length). False, with the
// reason in *why, otherwise.
bool YamlMatrix(const YAML::Node& node, std::vector<double>* values, int* rows, int* cols,
                std::string* why);

// Runs `read`, which walks the nodes of `path`, turning yaml-cpp's exceptions on a malformed
// structure (a key asked of a list, a conversion that fails) into p4::Error naming the file.
template <class Read>
auto ReadYamlFile(const std::string& path, Read&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw Error(path + ": malformed (" + e.what() + ")");
  }
}

}  // namespace p4
