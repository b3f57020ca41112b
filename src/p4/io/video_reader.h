// Reads a video through FFmpeg and delivers decoded frames as I420 with their presentation time
// (nanoseconds from the stream start). Files for now; devices and network streams open the same
// way (the tracking issue extends this reader).
#pragma once

#include <memory>
#include <string>

#include "p4/core/image.h"
#include "p4/core/time.h"

namespace p4 {

struct VideoInfo {
  int width = 0, height = 0;
  double fps = 0.0;
  int64_t frame_count = 0;  // from the container; 0 when unknown
};

class VideoReader {
 public:
  // Throws p4::Error naming the source when it cannot be opened or has no video stream.
  explicit VideoReader(const std::string& source);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  const VideoInfo& info() const;
  // The next frame; false at the end of the stream. Throws p4::Error on a decoding failure.
  bool Read(I420Image* frame, TimeNs* pts);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace p4
