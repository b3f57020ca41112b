// One pixel's samples in any of the camera formats (I420, NV12, YUYV). Internal to p4_segment.
#pragma once

#include <cstdint>

#include "p4/core/image.h"

namespace p4::segment::internal {

inline uint8_t LumaAt(const ImageView& image, int x, int y) {
  if (image.format == PixelFormat::kYUYV) return image.planes[0].Row(y)[2 * x];
  return image.planes[0].Row(y)[x];
}

// The chroma pair of the sample that covers pixel (x, y) (YUYV: the pair in its own row).
inline void ChromaAt(const ImageView& image, int x, int y, uint8_t* u, uint8_t* v) {
  switch (image.format) {
    case PixelFormat::kI420:
      *u = image.planes[1].Row(y / 2)[x / 2];
      *v = image.planes[2].Row(y / 2)[x / 2];
      return;
    case PixelFormat::kNV12: {
      const uint8_t* uv = image.planes[1].Row(y / 2) + 2 * (x / 2);
      *u = uv[0];
      *v = uv[1];
      return;
    }
    case PixelFormat::kYUYV: {
      const uint8_t* p = image.planes[0].Row(y) + 4 * (x / 2);
      *u = p[1];
      *v = p[3];
      return;
    }
  }
}

}  // namespace p4::segment::internal
