// Images as the cameras and decoders deliver them: YUV, 8 bit. Views do not own pixels; I420Image
// owns one frame in planar 4:2:0 (the format of H.264/FFV1 output and of most decoders).
#pragma once

#include <cstdint>
#include <vector>

namespace p4 {

enum class PixelFormat {
  kI420,  // planar Y, U, V; chroma at half width and half height
  kNV12,  // planar Y, interleaved UV at half width and half height
  kYUYV,  // packed Y0 U Y1 V, chroma at half width
};

// A non-owning view of one plane. stride is in bytes and may exceed width * bytes per sample.
struct PlaneView {
  const uint8_t* data = nullptr;
  int width = 0;
  int height = 0;
  int stride = 0;

  const uint8_t* Row(int y) const { return data + static_cast<std::ptrdiff_t>(y) * stride; }
};

// A non-owning view of a whole frame. For kI420 planes are Y, U, V; for kNV12 Y, UV; for kYUYV
// the single packed plane (width counts pixels, not bytes).
struct ImageView {
  PixelFormat format = PixelFormat::kI420;
  int width = 0;
  int height = 0;
  PlaneView planes[3];
};

// One owned I420 frame; width and height must be even.
class I420Image {
 public:
  I420Image() = default;
  I420Image(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  int chroma_width() const { return width_ / 2; }
  int chroma_height() const { return height_ / 2; }

  uint8_t* y() { return data_.data(); }
  uint8_t* u() { return y() + static_cast<std::size_t>(width_) * height_; }
  uint8_t* v() { return u() + static_cast<std::size_t>(chroma_width()) * chroma_height(); }
  const uint8_t* y() const { return data_.data(); }
  const uint8_t* u() const { return y() + static_cast<std::size_t>(width_) * height_; }
  const uint8_t* v() const {
    return u() + static_cast<std::size_t>(chroma_width()) * chroma_height();
  }

  std::vector<uint8_t>& bytes() { return data_; }
  const std::vector<uint8_t>& bytes() const { return data_; }

  ImageView View() const;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<uint8_t> data_;
};

}  // namespace p4

namespace p4 {

// The view scaled down by an integer factor (nearest sample) into I420, at
// (width / factor, height / factor) rounded down to even: cheap pictures for a live view.
// Precondition: factor >= 1 and the result at least 2x2.
void DownsampleToI420(const ImageView& view, int factor, I420Image* out);

}  // namespace p4
