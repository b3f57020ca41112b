// Colour classes on disk: YAML (or JSON) through OpenCV FileStorage,
//   classes:
//     - { name: ball_bright, y: [125, 240], u: [50, 100], v: [180, 240] }
// Names starting with "ball" make up the tracked ball. A file that a run learnt (`track --ball
// auto`) also gives the ball's lit colour (segment/ball_colour.h: 8-bit YUV, BT.601 limited
// range), which the background model's measures and the faint streak search use and which says
// whether the ball is white; optional:
//   ball_lit: [137, 65, 200]
#pragma once

#include <optional>
#include <string>

#include "p4/segment/ball_colour.h"
#include "p4/segment/color_classes.h"

namespace p4 {

struct ColorClassFile {
  segment::ColorClassSet classes;
  std::optional<segment::BallColour> ball;  // its ball_lit; nullopt without it
};

// Throws p4::Error naming the file, the class and the field: missing file, empty or corrupt
// file, no class, a bound outside 0-255 or reversed, more than 32 classes, no "ball" class; a
// ball_lit that is not three numbers or has a level outside 0-255 (the value named).
ColorClassFile ReadColorClassFile(const std::string& path);
// The classes alone (ReadColorClassFile's).
segment::ColorClassSet ReadColorClasses(const std::string& path);
// `ball`: written as ball_lit when given.
void WriteColorClasses(const segment::ColorClassSet& classes, const std::string& path,
                       const segment::BallColour* ball = nullptr);

}  // namespace p4
