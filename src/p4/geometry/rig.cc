#include "p4/geometry/rig.h"

#include <set>

namespace p4 {

int Rig::Find(const std::string& name) const {
  for (int i = 0; i < size(); ++i) {
    if (cameras[i].name == name) return i;
  }
  return -1;
}

std::vector<CameraClock> RigClocks(const Rig& rig) {
  std::vector<CameraClock> clocks;
  clocks.reserve(rig.cameras.size());
  for (const Camera& camera : rig.cameras) clocks.push_back(camera.clock);
  return clocks;
}

bool ValidateRig(const Rig& rig, std::string* error) {
  if (rig.cameras.empty()) {
    if (error) *error = "cameras: the rig has no camera";
    return false;
  }
  std::set<std::string> names;
  for (int i = 0; i < rig.size(); ++i) {
    const Camera& camera = rig.cameras[i];
    const std::string where = "cameras[" + std::to_string(i) + "] '" + camera.name + "': ";
    if (camera.name.empty()) {
      if (error) *error = "cameras[" + std::to_string(i) + "]: name is empty";
      return false;
    }
    if (!names.insert(camera.name).second) {
      if (error) *error = where + "name is used twice";
      return false;
    }
    std::string why;
    if (!ValidateCamera(camera, &why)) {
      if (error) *error = where + why;
      return false;
    }
  }
  return true;
}

}  // namespace p4
