// Synthetic frames for the segmentation tests: shapes painted in YUV on a background, with
// chroma averaged over 2x2 blocks as a camera's 4:2:0 output has it.
#pragma once

#include <algorithm>
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

// An orange ball (Y, U, V at full light: 150, 70, 200) lit by Lambert's law from `light` (image
// x right, y down, z toward the camera; unit) plus `ambient` of its light from all round, over a
// floor of one colour, blurred by a Gaussian of 0.8 px (lens and encoder), chroma averaged over
// 2x2 pixels; 64 x 48. The defaults: lit from above the camera, a quarter ambient, a red-brown
// floor as dark as the ball's shaded bottom.
inline I420Image ShadedBall(double cx, double cy, double r, Yuv floor_colour = {52.0, 112.0, 150.0},
                            double ambient = 0.25, const double light[3] = nullptr) {
  const int w = 64, h = 48;
  const double ball[3] = {150.0, 70.0, 200.0};
  const double floor[3] = {floor_colour.y, floor_colour.u, floor_colour.v};
  const double above[3] = {0.0, -0.6, 0.8};
  const double* l = light ? light : above;
  std::vector<double> planes[3];
  for (auto& p : planes) p.assign(static_cast<std::size_t>(w) * h, 0.0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int k = 0; k < 64; ++k) {
        const double dx = (x - 0.5 + (k % 8 + 0.5) / 8.0 - cx) / r;
        const double dy = (y - 0.5 + (k / 8 + 0.5) / 8.0 - cy) / r;
        const double rr = dx * dx + dy * dy;
        const double lit =
            rr <= 1.0 ? ambient + (1.0 - ambient) * std::max(0.0, dx * l[0] + dy * l[1] +
                                                                      std::sqrt(1.0 - rr) * l[2])
                      : 0.0;
        for (int c = 0; c < 3; ++c) {
          const double value = rr > 1.0 ? floor[c]
                               : c == 0 ? ball[0] * lit
                                        : 128.0 + (ball[c] - 128.0) * lit;
          planes[c][static_cast<std::size_t>(y) * w + x] += value / 64.0;
        }
      }
    }
  }
  const double sigma = 0.8;
  std::vector<double> kernel;
  for (int i = -3; i <= 3; ++i) kernel.push_back(std::exp(-0.5 * i * i / (sigma * sigma)));
  double total = 0.0;
  for (const double k : kernel) total += k;
  for (auto& plane : planes) {
    for (int pass = 0; pass < 2; ++pass) {  // rows, then columns
      std::vector<double> blurred(plane.size(), 0.0);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          for (int i = -3; i <= 3; ++i) {
            const int xx = pass == 0 ? std::clamp(x + i, 0, w - 1) : x;
            const int yy = pass == 1 ? std::clamp(y + i, 0, h - 1) : y;
            blurred[static_cast<std::size_t>(y) * w + x] +=
                kernel[static_cast<std::size_t>(i + 3)] / total *
                plane[static_cast<std::size_t>(yy) * w + xx];
          }
        }
      }
      plane.swap(blurred);
    }
  }
  I420Image image(w, h);
  for (std::size_t i = 0; i < planes[0].size(); ++i) {
    image.y()[i] = static_cast<uint8_t>(std::lround(planes[0][i]));
  }
  for (int y = 0; y < h / 2; ++y) {
    for (int x = 0; x < w / 2; ++x) {
      const std::size_t i = static_cast<std::size_t>(2 * y) * w + 2 * x;
      const auto mean = [&](const std::vector<double>& p) {
        return static_cast<uint8_t>(std::lround((p[i] + p[i + 1] + p[i + w] + p[i + w + 1]) / 4));
      };
      image.u()[y * (w / 2) + x] = mean(planes[1]);
      image.v()[y * (w / 2) + x] = mean(planes[2]);
    }
  }
  return image;
}

}  // namespace p4::segment::testing
