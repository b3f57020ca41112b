// Colour classes on disk: YAML (or JSON) through OpenCV FileStorage,
//   classes:
//     - { name: ball_bright, y: [125, 240], u: [50, 100], v: [180, 240] }
// Names starting with "ball" make up the tracked ball.
#pragma once

#include <string>

#include "p4/segment/color_classes.h"

namespace p4 {

// Throws p4::Error naming the file, the class and the field: missing file, empty or corrupt
// file, no class, a bound outside 0-255 or reversed, more than 32 classes, no "ball" class.
segment::ColorClassSet ReadColorClasses(const std::string& path);
void WriteColorClasses(const segment::ColorClassSet& classes, const std::string& path);

}  // namespace p4
