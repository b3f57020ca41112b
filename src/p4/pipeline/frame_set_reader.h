// N video sources grouped into time-stamped frame sets (DESIGN.md "The loop"). A set takes the
// earliest pending frame's time; each source contributes its frame when it lies within half the
// fastest source's frame period of it (a 60 fps camera beside a 120 fps one joins the set of
// the 120 fps frame taken with it, not the one half its period before). A source that ends early,
// or lacks a frame, leaves its camera out of the set; the run goes on until every source has ended.
// Damaged stretches of a source are skipped (VideoReader) and handed over by TakeGaps(); a source
// that fails while reading (a cut file, a lost connection) ends there, with its reason kept in
// ended_with_error(). With `loop`, video files start again when every source has ended, their times
// continuing (shifted by the span played plus one frame period), so a recording plays for as long
// as the run lasts (a kiosk at a club, or a live view that must stay up until a viewer has seen
// it).
#pragma once

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

class FrameSetReader {
 public:
  // Opens every source; throws p4::Error naming the one that fails, or when `loop` is asked of a
  // live source (it cannot start again).
  // `clocks` (one per source, or empty: all in step) map each source's timestamps to the rig's
  // time (geometry/camera_clock.h) before frames are grouped.
  explicit FrameSetReader(const std::vector<std::string>& sources, bool loop = false,
                          std::vector<CameraClock> clocks = {});

  bool Next(FrameSet* set);
  int size() const { return static_cast<int>(sources_.size()); }
  const VideoInfo& info(int i) const { return sources_[i].reader->info(); }
  const std::string& name(int i) const { return sources_[i].name; }
  const std::vector<std::string>& ended_with_error() const { return errors_; }
  // The damaged stretches closed since the last call, in the order they were met.
  std::vector<SourceGap> TakeGaps();
  int loops() const { return loops_; }  // times the files have started again

 private:
  struct Source {
    std::string name;
    std::unique_ptr<VideoReader> reader;
    CameraClock clock;
    ImageView view;
    TimeNs pts = 0;  // in the rig's clock
    bool has_frame = false;
    bool consumed = true;
    bool ended = false;
  };
  bool ReadAll();     // the next frame of every source whose last one was used
  bool StartAgain();  // loop: reopens every file, times shifted past the last one

  std::vector<Source> sources_;
  std::vector<std::string> errors_;
  std::vector<SourceGap> gaps_;
  bool loop_ = false;
  int loops_ = 0;
  TimeNs first_pts_ = 0, last_pts_ = 0, shift_ = 0;
  TimeNs tolerance_ = 0;  // half the fastest source's frame period: a set's reach
  bool any_frame_ = false;
};

}  // namespace p4
