// A rig: the calibrated cameras of one installation, in one world frame (DESIGN.md). Files are
// read and written by p4/io/rig_file.h.
#pragma once

#include <string>
#include <vector>

#include "p4/geometry/camera.h"

namespace p4 {

struct Rig {
  std::vector<Camera> cameras;

  int size() const { return static_cast<int>(cameras.size()); }
  // Index of the camera with this name, or -1.
  int Find(const std::string& name) const;
};

// Every camera's clock, in the rig's order.
std::vector<CameraClock> RigClocks(const Rig& rig);

// At least one camera, every camera valid (ValidateCamera), names unique and non-empty.
// On failure *error names the camera and the field.
bool ValidateRig(const Rig& rig, std::string* error);

}  // namespace p4
