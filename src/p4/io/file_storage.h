// Opening OpenCV FileStorage (YAML/JSON) files for reading, with P4's errors (internal to p4/io).
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "p4/core/error.h"

namespace p4 {

// Opens `path` and returns the top-level list `key`. Throws p4::Error naming the file for a
// missing, empty or unparsable file or a missing list. `fs` keeps the nodes alive.
inline cv::FileNode OpenList(const std::string& path, const char* key, cv::FileStorage* fs) {
  if (!std::filesystem::exists(path)) throw Error(path + ": no such file");
  if (std::filesystem::file_size(path) == 0) throw Error(path + ": the file is empty");
  try {
    if (!fs->open(path, cv::FileStorage::READ))
      throw Error(path + ": cannot open or parse the file");
  } catch (const cv::Exception& e) {
    throw Error(path + ": cannot parse the file (" + e.msg + ")");
  }
  const cv::FileNode list = (*fs)[key];
  if (list.empty() || !list.isSeq()) throw Error(path + ": missing '" + key + "' list");
  return list;
}

}  // namespace p4
