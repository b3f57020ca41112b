// Reads video through FFmpeg (libavformat/libavcodec/libavdevice): files, V4L2 devices
// (/dev/videoN) and network streams (rtsp://, udp://, tcp://, http://). Frames come with their
// presentation time in nanoseconds from the stream's start, in their native YUV format when it is
// I420, NV12 or YUYV (no conversion), converted to I420 otherwise.
//
// Damaged input loses only what is damaged: packets the decoder refuses and frames it flags as
// corrupt (concealed, or missing a reference) are skipped, and each stretch of them is kept as a
// VideoGap (where, how many frames) for the caller to report. Only a source that cannot be opened
// is an error; one whose container cannot be read on ends there, as at its end, with the reason
// kept in ended_with().
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/core/time.h"

namespace p4 {

struct VideoInfo {
  int width = 0, height = 0;
  double fps = 0.0;
  int64_t frame_count = 0;  // from the container; 0 when unknown
};

// FFmpeg's own messages (a decoder's "error while decoding MB ..." for each damaged picture):
// shown when `verbose`, else only its fatal ones (P4 reports what was lost). Process-wide.
void ShowFfmpegMessages(bool verbose);

// A stretch of a source that could not be decoded: the frames between two good ones.
struct VideoGap {
  std::optional<TimeNs> after;   // the last good frame's time before it; none at the start
  std::optional<TimeNs> before;  // the first good frame's time after it; none at the end
  int64_t frames_lost = 0;       // by the stream's frame rate (at least the frames skipped)
  int64_t damaged = 0;           // packets refused and frames flagged corrupt in it
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
  // The next good frame as a view into the decoder's buffer, valid until the next call; false at
  // the end of the stream, or when the container cannot be read on (ended_with() says why).
  bool ReadView(ImageView* view, TimeNs* pts);
  // The next frame copied (and converted if need be) into an I420 image.
  bool Read(I420Image* frame, TimeNs* pts);

  // The stretches skipped so far, each once: a gap is handed over when the good frame after it
  // is (or at the end). Clears the list.
  std::vector<VideoGap> TakeGaps();
  // Why the stream ended before its end ("" when it did not: the end, or not yet).
  const std::string& ended_with() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace p4
