// The paper's segmentation (LUT classes, run-length rows, union-find regions) on arbitrary image
// bytes: the first bytes choose the size (2-256 x 2-256, even), the pixel format, the stride and
// a region of interest (any, even outside the image); the rest are the pixels (repeated to fill).
#include <cstring>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/blob_finder.h"
#include "p4/segment/color_classes.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 8) return 0;
  const int width = 2 * (1 + data[0] % 128), height = 2 * (1 + data[1] % 128);
  const auto format = static_cast<p4::PixelFormat>(data[2] % 3);
  p4::segment::SegmentOptions options;
  options.stride = 1 + data[3] % 4;
  p4::segment::Roi roi;
  roi.x0 = static_cast<int8_t>(data[4]) * 2;
  roi.y0 = static_cast<int8_t>(data[5]) * 2;
  roi.x1 = roi.x0 + data[6];
  roi.y1 = roi.y0 + data[7];
  // Pixels: I420 and NV12 take w*h*3/2 bytes, YUYV w*h*2.
  const std::size_t bytes = static_cast<std::size_t>(width) * height * 2;
  std::vector<uint8_t> pixels(bytes);
  const uint8_t* body = data + 8;
  const std::size_t body_size = size - 8;
  for (std::size_t i = 0; i < bytes; ++i) pixels[i] = body_size ? body[i % body_size] : 0;
  p4::ImageView view;
  view.format = format;
  view.width = width;
  view.height = height;
  uint8_t* y = pixels.data();
  uint8_t* chroma = y + static_cast<std::size_t>(width) * height;
  switch (format) {
    case p4::PixelFormat::kI420:
      view.planes[0] = {y, width, height, width};
      view.planes[1] = {chroma, width / 2, height / 2, width / 2};
      view.planes[2] = {chroma + width / 2 * (height / 2), width / 2, height / 2, width / 2};
      break;
    case p4::PixelFormat::kNV12:
      view.planes[0] = {y, width, height, width};
      view.planes[1] = {chroma, width / 2, height / 2, width};
      break;
    case p4::PixelFormat::kYUYV:
      view.planes[0] = {y, width, height, 2 * width};
      break;
  }
  static const p4::segment::ColorLut lut = p4::segment::DefaultOrangeBall().BuildLut();
  static p4::segment::BlobFinder finder;
  std::vector<p4::segment::Region> regions;
  const int n = finder.Find(view, lut, roi, options, &regions);
  if (n < 0 || n > static_cast<int>(regions.size())) __builtin_trap();
  for (int k = 0; k < n; ++k) {
    const auto& r = regions[k];
    // A region lies in the image and has the area it says.
    if (r.area <= 0 || r.cx < -0.5 || r.cy < -0.5 || r.cx > width || r.cy > height) {
      __builtin_trap();
    }
  }
  return 0;
}
