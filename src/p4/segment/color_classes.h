// Colour classes as boxes in YUV, encoded in three look-up tables of 32-bit masks (paper §3.1,
// after Bruce, Balch and Veloso's CMVision): a pixel (y, u, v) belongs to class k when bit k of
// Y[y] & U[u] & V[v] is set, so up to 32 classes are tested with two ANDs. Several small boxes
// make up one object ("ball"), because a ball's colours do not fill one box well.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace p4::segment {

// A box in YUV (8-bit values as the camera delivers them; bounds inclusive).
struct ColorClass {
  std::string name;
  std::array<uint8_t, 2> y{0, 255}, u{0, 255}, v{0, 255};

  bool Contains(uint8_t yy, uint8_t uu, uint8_t vv) const {
    return yy >= y[0] && yy <= y[1] && uu >= u[0] && uu <= u[1] && vv >= v[0] && vv <= v[1];
  }
  bool IsValid(std::string* error) const;
};

// The three tables. Bit k of each entry belongs to the class set at index k.
struct ColorLut {
  std::array<uint32_t, 256> y{}, u{}, v{};

  uint32_t Classify(uint8_t yy, uint8_t uu, uint8_t vv) const { return y[yy] & u[uu] & v[vv]; }
};

// Up to 32 named classes; `object` groups classes that make up the tracked object.
struct ColorClassSet {
  std::vector<ColorClass> classes;

  // At most 32 classes, each valid. On failure *error names the class.
  bool IsValid(std::string* error) const;
  ColorLut BuildLut() const;
  // Mask of the classes whose name starts with `prefix` (e.g. "ball" for ball_0, ball_1, ...).
  uint32_t MaskOf(const std::string& prefix) const;
};

// Classes for an orange ball under indoor light, in BT.601 limited range (as webcams deliver):
// three boxes from the ball's bright highlight to its shaded side.
ColorClassSet DefaultOrangeBall();
// Classes for a white ball (bright, nearly neutral chroma).
ColorClassSet DefaultWhiteBall();
// Classes for a yellow ball.
ColorClassSet DefaultYellowBall();
// The classes of a named ball: "white", "yellow", anything else orange (the paper's colour).
ColorClassSet NamedBall(const std::string& name);

struct YuvSample {
  uint8_t y, u, v;
};

// Learns `boxes` classes named `name`_0.. from pixels of the object: the samples are split into
// `boxes` bands of luma (the ball's shading runs along Y), and each band gets the box around its
// samples' 2nd-98th percentiles widened by `margin`. Precondition: samples not empty.
std::vector<ColorClass> LearnClasses(std::span<const YuvSample> samples, const std::string& name,
                                     int boxes = 3, int margin = 6);

}  // namespace p4::segment
