// Reading and writing rig files (DESIGN.md "Rig"): OpenCV FileStorage YAML, or JSON with the same
// keys (chosen by the file's extension). Matrices may be OpenCV matrices ({rows, cols, data}) or,
// in hand-written files, plain (nested) number lists.
#pragma once

#include <map>
#include <string>

#include "p4/geometry/rig.h"

namespace p4 {

// Throws p4::Error naming the file, the camera and the field for: an unreadable or unparsable
// file, missing keys, wrong matrix sizes, non-finite numbers, a rotation that is not a rotation,
// zero focal lengths, duplicate names.
Rig ReadRig(const std::string& path);

// Writes `.yaml`/`.yml` or `.json` (by extension) atomically (temporary file, then rename).
// `reprojection_error_px` (by camera name, optional) is written beside each camera it names as
// `reprojection_error_px`, the RMS of its calibration; readers ignore it.
// Throws p4::Error when the rig is invalid or the file cannot be written.
void WriteRig(const Rig& rig, const std::string& path,
              const std::map<std::string, double>& reprojection_error_px = {});

}  // namespace p4
