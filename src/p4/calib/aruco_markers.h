// ArUco markers as module grids (OpenCV 4.6 contrib aruco), for scenes and printouts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace p4 {

// OpenCV's predefined dictionary id for a name such as "DICT_4X4_50"; throws p4::Error naming
// the value for an unknown name.
int ArucoDictionaryId(const std::string& name);

// The marker's modules with a 1-module black border: cells x cells values, 1 = black.
std::vector<uint8_t> ArucoModules(const std::string& dictionary, int id, int* cells);

}  // namespace p4
