// Synthetic frames for the segmentation tests: shapes painted in YUV on a background, with
// chroma averaged over 2x2 blocks as a camera's 4:2:0 output has it.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "p4/core/image.h"

namespace p4::segment::testing {

struct Yuv {
  double y, u, v;
};

inline constexpr Yuv kOrange{137.0, 65.0, 199.0};
inline constexpr Yuv kTableBlue{44.0, 150.0, 115.0};

// `inside(x, y)` is the coverage in [0, 1] of pixel (x, y) by the object.
inline I420Image Paint(int w, int h, const std::function<double(double, double)>& inside,
                       Yuv object = kOrange, Yuv background = kTableBlue) {
  I420Image image(w, h);
  std::vector<double> u(static_cast<std::size_t>(w) * h), v(u.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double a = inside(x, y);
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      image.y()[i] = static_cast<uint8_t>(std::lround(a * object.y + (1 - a) * background.y));
      u[i] = a * object.u + (1 - a) * background.u;
      v[i] = a * object.v + (1 - a) * background.v;
    }
  }
  for (int y = 0; y < h / 2; ++y) {
    for (int x = 0; x < w / 2; ++x) {
      const std::size_t i = static_cast<std::size_t>(2 * y) * w + 2 * x;
      image.u()[y * (w / 2) + x] =
          static_cast<uint8_t>(std::lround((u[i] + u[i + 1] + u[i + w] + u[i + w + 1]) / 4));
      image.v()[y * (w / 2) + x] =
          static_cast<uint8_t>(std::lround((v[i] + v[i + 1] + v[i + w] + v[i + w + 1]) / 4));
    }
  }
  return image;
}

// Coverage of a pixel by a disc, by 8x8 supersampling.
inline double Disc(double x, double y, double cx, double cy, double r) {
  int hits = 0;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double dx = x - 0.5 + (i + 0.5) / 8 - cx, dy = y - 0.5 + (j + 0.5) / 8 - cy;
      hits += dx * dx + dy * dy <= r * r;
    }
  }
  return hits / 64.0;
}

}  // namespace p4::segment::testing
