#include "p4/pipeline/frame_set_reader.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

#include "p4/core/error.h"

namespace p4 {

FrameSetReader::FrameSetReader(const std::vector<std::string>& sources, bool loop,
                               std::vector<CameraClock> clocks)
    : loop_(loop) {
  if (!clocks.empty() && clocks.size() != sources.size()) {
    throw Error("frame sets: " + std::to_string(clocks.size()) + " camera clocks for " +
                std::to_string(sources.size()) + " sources");
  }
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::string& s = sources[i];
    if (loop && VideoReader::IsLive(s)) {
      throw Error(s + ": a live source cannot loop (only video files start again)");
    }
    Source source;
    source.name = s;
    source.reader = std::make_unique<VideoReader>(s);
    if (!clocks.empty()) source.clock = clocks[i];
    sources_.push_back(std::move(source));
  }
  double fastest = 0.0;
  for (const Source& s : sources_) fastest = std::max(fastest, s.reader->info().fps);
  tolerance_ = FromSeconds(0.5 / (fastest > 0 ? fastest : 30.0));
}

bool FrameSetReader::ReadAll() {
  bool any = false;
  for (Source& s : sources_) {
    if (s.consumed && !s.ended) {
      try {
        s.has_frame = s.reader->ReadView(&s.view, &s.pts);
        if (!s.has_frame && !s.reader->ended_with().empty()) {
          errors_.push_back(s.reader->ended_with());
        }
      } catch (const Error& e) {
        // One source's failure ends that source, never the run.
        errors_.push_back(e.what());
        s.has_frame = false;
      }
      for (const VideoGap& g : s.reader->TakeGaps()) {
        gaps_.push_back({static_cast<int>(&s - sources_.data()), g});
      }
      if (s.has_frame) {
        s.pts = s.clock.WorldTime(s.pts) + shift_;
        if (!any_frame_ || s.pts < first_pts_) first_pts_ = s.pts;
        last_pts_ = any_frame_ ? std::max(last_pts_, s.pts) : s.pts;
        any_frame_ = true;
      }
      s.ended = !s.has_frame;
      s.consumed = false;
    }
    any = any || (s.has_frame && !s.consumed);
  }
  return any;
}

std::vector<SourceGap> FrameSetReader::TakeGaps() { return std::exchange(gaps_, {}); }

bool FrameSetReader::StartAgain() {
  if (!loop_ || !any_frame_) return false;
  double fps = 0.0;
  for (Source& s : sources_) {
    s.reader = std::make_unique<VideoReader>(s.name);
    s.has_frame = false;
    s.consumed = true;
    s.ended = false;
    fps = std::max(fps, s.reader->info().fps);
  }
  // The next pass starts one frame period after the last frame of this one.
  const TimeNs period = FromSeconds(1.0 / (fps > 0 ? fps : 30.0));
  // (first_pts_ is the first pass's first frame: the files' own start.)
  shift_ = last_pts_ + period - first_pts_;
  ++loops_;
  return true;
}

bool FrameSetReader::Next(FrameSet* set) {
  if (!ReadAll() && !(StartAgain() && ReadAll())) return false;
  std::optional<TimeNs> t;
  for (const Source& s : sources_) {
    if (s.has_frame && !s.consumed && (!t || s.pts < *t)) t = s.pts;
  }
  set->t = *t;
  set->images.assign(sources_.size(), std::nullopt);
  set->times.assign(sources_.size(), *t);
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    Source& s = sources_[i];
    if (!s.has_frame || s.consumed) continue;
    if (std::llabs(s.pts - *t) <= tolerance_) {
      set->images[i] = s.view;
      set->times[i] = s.pts;
      s.consumed = true;
    }
  }
  return true;
}

}  // namespace p4
