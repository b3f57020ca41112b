// ReadRig on any bytes, as YAML (OpenCV FileStorage) or JSON (nlohmann) by the first byte.
#include "fuzz_input.h"
#include "p4/core/error.h"
#include "p4/io/rig_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* extension = (data[0] & 1) != 0 ? ".json" : ".yaml";
  const std::string path = p4::fuzz::WriteInput(data + 1, size - 1, extension);
  try {
    const p4::Rig rig = p4::ReadRig(path);
    // A rig that reads is valid: every camera casts a ray through its centre pixel and projects
    // a point along it.
    for (const auto& c : rig.cameras) {
      const Eigen::Vector2d centre(c.cx, c.cy);
      (void)c.Project(c.Center() + c.RayDirection(centre));
    }
  } catch (const p4::Error&) {
  }
  return 0;
}
