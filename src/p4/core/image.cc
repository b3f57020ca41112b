#include "p4/core/image.h"

#include <cassert>

namespace p4 {

I420Image::I420Image(int width, int height)
    : width_(width), height_(height), data_(static_cast<std::size_t>(width) * height * 3 / 2, 0) {
  assert(width % 2 == 0 && height % 2 == 0);
}

ImageView I420Image::View() const {
  ImageView view;
  view.format = PixelFormat::kI420;
  view.width = width_;
  view.height = height_;
  view.planes[0] = {y(), width_, height_, width_};
  view.planes[1] = {u(), chroma_width(), chroma_height(), chroma_width()};
  view.planes[2] = {v(), chroma_width(), chroma_height(), chroma_width()};
  return view;
}

}  // namespace p4

namespace p4 {

void DownsampleToI420(const ImageView& view, int factor, I420Image* out) {
  const int w = (view.width / factor) & ~1, h = (view.height / factor) & ~1;
  if (out->width() != w || out->height() != h) *out = I420Image(w, h);
  const int cw = w / 2, ch = h / 2;
  uint8_t* y = out->y();
  uint8_t* u = out->u();
  uint8_t* v = out->v();
  for (int r = 0; r < h; ++r) {
    const uint8_t* row = view.planes[0].Row(r * factor);
    for (int c = 0; c < w; ++c) {
      y[r * w + c] = view.format == PixelFormat::kYUYV ? row[2 * c * factor] : row[c * factor];
    }
  }
  for (int r = 0; r < ch; ++r) {
    const int sy = 2 * r * factor;  // source row of this chroma sample, in full resolution
    for (int c = 0; c < cw; ++c) {
      const int sx = 2 * c * factor;
      uint8_t cu = 128, cv = 128;
      switch (view.format) {
        case PixelFormat::kI420:
          cu = view.planes[1].Row(sy / 2)[sx / 2];
          cv = view.planes[2].Row(sy / 2)[sx / 2];
          break;
        case PixelFormat::kNV12:
          cu = view.planes[1].Row(sy / 2)[2 * (sx / 2)];
          cv = view.planes[1].Row(sy / 2)[2 * (sx / 2) + 1];
          break;
        case PixelFormat::kYUYV: {
          const uint8_t* row = view.planes[0].Row(sy);
          cu = row[4 * (sx / 2) + 1];
          cv = row[4 * (sx / 2) + 3];
          break;
        }
      }
      u[r * cw + c] = cu;
      v[r * cw + c] = cv;
    }
  }
}

}  // namespace p4
