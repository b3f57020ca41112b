// Reads video through FFmpeg (libavformat/libavcodec/libavdevice): files, V4L2 devices
// (/dev/videoN) and network streams (rtsp://, udp://, tcp://, http://). Frames come with their
// presentation time in nanoseconds from the stream's start, in their native YUV format when it is
// I420, NV12 or YUYV (no conversion), converted to I420 otherwise.
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

  // True for sources that are devices or network streams rather than files.
  static bool IsLive(const std::string& source);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  const VideoInfo& info() const;
  // The next frame as a view into the decoder's buffer, valid until the next call; false at the
  // end of the stream. Throws p4::Error on a decoding failure.
  bool ReadView(ImageView* view, TimeNs* pts);
  // The next frame copied (and converted if need be) into an I420 image.
  bool Read(I420Image* frame, TimeNs* pts);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace p4
