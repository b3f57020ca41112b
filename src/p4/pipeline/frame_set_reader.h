// N video sources grouped into time-stamped frame sets (DESIGN.md "The loop"). A set takes the
// earliest pending frame's time; each source contributes its frame when it lies within half a
// frame period of it. A source that ends early, or lacks a frame, leaves its camera out of the
// set; the run goes on until every source has ended. A live source (device, stream) that fails
// while reading ends there too, with its error kept in ended_with_error().
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/core/time.h"
#include "p4/io/video_reader.h"

namespace p4 {

struct FrameSet {
  TimeNs t = 0;
  std::vector<std::optional<ImageView>> images;  // one per source; views valid until Next()
};

class FrameSetReader {
 public:
  // Opens every source; throws p4::Error naming the one that fails.
  explicit FrameSetReader(const std::vector<std::string>& sources);

  bool Next(FrameSet* set);
  int size() const { return static_cast<int>(sources_.size()); }
  const VideoInfo& info(int i) const { return sources_[i].reader->info(); }
  const std::string& name(int i) const { return sources_[i].name; }
  const std::vector<std::string>& ended_with_error() const { return errors_; }

 private:
  struct Source {
    std::string name;
    std::unique_ptr<VideoReader> reader;
    ImageView view;
    TimeNs pts = 0;
    bool has_frame = false;
    bool consumed = true;
    bool ended = false;
  };
  std::vector<Source> sources_;
  std::vector<std::string> errors_;
};

}  // namespace p4
