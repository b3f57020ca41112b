#include "p4/pipeline/frame_set_reader.h"

#include <algorithm>
#include <cstdlib>

#include "p4/core/error.h"

namespace p4 {

FrameSetReader::FrameSetReader(const std::vector<std::string>& sources) {
  for (const auto& s : sources) {
    Source source;
    source.name = s;
    source.reader = std::make_unique<VideoReader>(s);
    sources_.push_back(std::move(source));
  }
}

bool FrameSetReader::Next(FrameSet* set) {
  for (Source& s : sources_) {
    if (s.consumed && !s.ended) {
      try {
        s.has_frame = s.reader->ReadView(&s.view, &s.pts);
      } catch (const Error& e) {
        if (!VideoReader::IsLive(s.name)) throw;  // a broken file is an error of the run
        errors_.push_back(e.what());
        s.has_frame = false;
      }
      s.ended = !s.has_frame;
      s.consumed = false;
    }
  }
  std::optional<TimeNs> t;
  for (const Source& s : sources_) {
    if (s.has_frame && !s.consumed && (!t || s.pts < *t)) t = s.pts;
  }
  if (!t) return false;
  set->t = *t;
  set->images.assign(sources_.size(), std::nullopt);
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    Source& s = sources_[i];
    if (!s.has_frame || s.consumed) continue;
    const double fps = s.reader->info().fps > 0 ? s.reader->info().fps : 30.0;
    const TimeNs tolerance = FromSeconds(0.5 / fps);
    if (std::llabs(s.pts - *t) <= tolerance) {
      set->images[i] = s.view;
      s.consumed = true;
    }
  }
  return true;
}

}  // namespace p4
