// Writes I420 frames to a video file through FFmpeg (libavformat/libavcodec): H.264 (libx264,
// in .mp4) or lossless FFV1 (in .mkv). Frame k is stamped k / fps. Colour: BT.601, limited range.
#pragma once

#include <memory>
#include <string>

#include "p4/core/image.h"
#include "p4/core/time.h"

namespace p4 {

enum class VideoCodec { kH264, kFFV1 };

struct VideoWriterOptions {
  int width = 0, height = 0;  // even
  int fps = 120;
  VideoCodec codec = VideoCodec::kH264;
  int crf = 18;  // H.264 quality (lower is better)
  std::string preset = "ultrafast";
  int threads = 1;  // encoder threads
  // Resolution of the frames' timestamps, ticks a second (0: one tick a frame). Stamps off the
  // frame grid (jitter, a clock's drift) need more, e.g. 90000.
  int time_base_hz = 0;

  bool IsValid(std::string* error) const;
};

// File extension for a codec: ".mp4" or ".mkv".
const char* VideoExtension(VideoCodec codec);

class VideoWriter {
 public:
  // Throws p4::Error naming the file when it cannot be opened or the codec is missing.
  VideoWriter(const std::string& path, const VideoWriterOptions& options);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  void Write(const I420Image& frame);  // the next frame, stamped k / fps; throws p4::Error on
                                       // encoder failure
  // A frame stamped `stamp` (from the recording's start; rounded to the time base), later than
  // the last one written: frames can be dropped or stamped off the grid.
  void Write(const I420Image& frame, TimeNs stamp);
  void Close();  // flushes and writes the trailer; idempotent

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace p4
