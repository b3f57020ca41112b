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
