// N video sources grouped into time-stamped frame sets (DESIGN.md "The loop"). A set takes the
// earliest pending frame's time; each source contributes its frame when it lies within half the
// fastest source's frame period of it (a 60 fps camera beside a 120 fps one joins the set of
// the 120 fps frame taken with it, not the one half its period before). A source that ends early,
// or lacks a frame, leaves its camera out of the set; the run goes on until every source has ended.
// Damaged stretches of a source are skipped (VideoReader) and handed over by TakeGaps(). A file
// that fails while reading (cut short) ends there, with its reason kept in ended_with_error(). A
// live source (device, stream) that fails or ends is opened again in the background, with a
// backoff, while the other cameras go on (its camera is out of the sets meanwhile); its frames
// after the return are placed in time by the wall clock (its new stream's times start again).
// TakeSourceEvents() says when a source was lost and when it came back. With `loop`, video files
// start again when every source has ended, their times continuing (shifted by the span played plus
// one frame period), so a recording plays for as long as the run lasts (a kiosk at a club, or a
// live view that must stay up until a viewer has seen it).
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/core/time.h"
#include "p4/geometry/camera_clock.h"
#include "p4/io/video_reader.h"

namespace p4 {

struct FrameSet {
  TimeNs t = 0;                                  // the earliest image's time
  std::vector<std::optional<ImageView>> images;  // one per source; views valid until Next()
  std::vector<TimeNs> times;  // each image's own time in the rig's clock (top row), ns
};

// A damaged stretch of one source (times in the source's own clock: seconds into the file).
struct SourceGap {
  int source = 0;
  VideoGap gap;
};

// A live source lost or back.
struct SourceEvent {
  int source = 0;
  bool back = false;          // false: lost (reconnecting)
  double seconds_away = 0.0;  // back: how long it was lost
  std::string reason;         // lost: why (without the source's name)
};

struct FrameSetReaderOptions {
  bool loop = false;  // play the files again when every source has ended (not for live ones)
  // Per source (or empty: all in step): each source's timestamps to the rig's time
  // (geometry/camera_clock.h), applied before frames are grouped.
  std::vector<CameraClock> clocks;
  // Live sources that fail or end are opened again, reconnect_min_s after, then twice as long
  // after each try that fails, up to reconnect_max_s between tries (a camera that returns is
  // read again within about that); false: they end.
  bool reconnect = true;
  double reconnect_min_s = 0.25;
  double reconnect_max_s = 1.0;
  // Set by another thread: Next() stops waiting for a source to come back and returns false.
  const std::atomic<bool>* stop = nullptr;

  bool IsValid(std::string* error) const;
};

class Reconnector;

class FrameSetReader {
 public:
  // Opens every source; throws p4::Error naming the one that fails, or when `loop` is asked of a
  // live source (it cannot start again).
  // `clocks` (one per source, or empty: all in step) map each source's timestamps to the rig's
  // time (geometry/camera_clock.h) before frames are grouped.
  explicit FrameSetReader(const std::vector<std::string>& sources, bool loop = false,
                          std::vector<CameraClock> clocks = {});
  FrameSetReader(const std::vector<std::string>& sources, FrameSetReaderOptions options);
  ~FrameSetReader();
  FrameSetReader(const FrameSetReader&) = delete;
  FrameSetReader& operator=(const FrameSetReader&) = delete;

  bool Next(FrameSet* set);
  int size() const { return static_cast<int>(sources_.size()); }
  const VideoInfo& info(int i) const { return sources_[i].info; }
  const std::string& name(int i) const { return sources_[i].name; }
  const std::vector<std::string>& ended_with_error() const { return errors_; }
  // The damaged stretches closed since the last call, in the order they were met.
  std::vector<SourceGap> TakeGaps();
  // Live sources lost and back since the last call, in order.
  std::vector<SourceEvent> TakeSourceEvents();
  int loops() const { return loops_; }  // times the files have started again

 private:
  struct Source {
    std::string name;
    std::unique_ptr<VideoReader> reader;
    VideoInfo info;  // as first opened
    CameraClock clock;
    bool live = false;
    std::unique_ptr<Reconnector> reconnect;  // while lost
    std::chrono::steady_clock::time_point lost_at;
    bool rebase = false;  // back: the next frame sets live_shift
    TimeNs live_shift = 0;
    ImageView view;
    TimeNs pts = 0;  // in the rig's clock
    bool has_frame = false;
    bool consumed = true;
    bool ended = false;
  };
  bool ReadAll();  // the next frame of every source whose last one was used
  void Lost(Source* s, const std::string& reason);
  bool Reconnecting() const;
  bool StartAgain();  // loop: reopens every file, times shifted past the last one

  std::vector<Source> sources_;
  std::vector<std::string> errors_;
  std::vector<SourceGap> gaps_;
  std::vector<SourceEvent> events_;
  FrameSetReaderOptions options_;
  // The wall clock of the first frame: a live source's time after it comes back.
  std::optional<std::chrono::steady_clock::time_point> first_wall_;
  int loops_ = 0;
  TimeNs first_pts_ = 0, last_pts_ = 0, shift_ = 0;
  TimeNs tolerance_ = 0;  // half the fastest source's frame period: a set's reach
  bool any_frame_ = false;
};

}  // namespace p4
