#include "p4/pipeline/frame_set_reader.h"

#include <algorithm>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>
#include <utility>

#include "p4/core/error.h"

namespace p4 {

// Opens a live source again in its own thread, trying with a growing wait until it opens or the
// reader is destroyed.
class Reconnector {
 public:
  Reconnector(std::string source, double min_s, double max_s)
      : thread_([this, source = std::move(source), min_s, max_s] { Run(source, min_s, max_s); }) {}
  ~Reconnector() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  Reconnector(const Reconnector&) = delete;
  Reconnector& operator=(const Reconnector&) = delete;

  // The source opened again, once; null until then.
  std::unique_ptr<VideoReader> Take() {
    std::lock_guard lock(mutex_);
    return std::move(ready_);
  }

 private:
  void Run(const std::string& source, double min_s, double max_s) {
    double wait_s = min_s;
    std::unique_lock lock(mutex_);
    while (!stop_) {
      if (wake_.wait_for(lock, std::chrono::duration<double>(wait_s), [this] { return stop_; })) {
        return;
      }
      lock.unlock();
      std::unique_ptr<VideoReader> reader;
      try {
        reader = std::make_unique<VideoReader>(source);
      } catch (const Error&) {
      }
      lock.lock();
      if (reader) {
        ready_ = std::move(reader);
        return;
      }
      wait_s = std::min(2.0 * wait_s, max_s);
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::unique_ptr<VideoReader> ready_;
  std::thread thread_;  // last: started when the rest is ready
};

bool FrameSetReaderOptions::IsValid(std::string* error) const {
  if (!(reconnect_min_s > 0.0) || !(reconnect_max_s >= reconnect_min_s)) {
    *error = "reconnect waits must be positive, the longest no shorter than the first";
    return false;
  }
  return true;
}

FrameSetReader::FrameSetReader(const std::vector<std::string>& sources, bool loop,
                               std::vector<CameraClock> clocks)
    : FrameSetReader(sources, [&] {
        FrameSetReaderOptions o;
        o.loop = loop;
        o.clocks = std::move(clocks);
        return o;
      }()) {}

FrameSetReader::FrameSetReader(const std::vector<std::string>& sources,
                               FrameSetReaderOptions options)
    : options_(std::move(options)) {
  std::string why;
  if (!options_.IsValid(&why)) throw Error("frame sets: " + why);
  const std::vector<CameraClock>& clocks = options_.clocks;
  if (!clocks.empty() && clocks.size() != sources.size()) {
    throw Error("frame sets: " + std::to_string(clocks.size()) + " camera clocks for " +
                std::to_string(sources.size()) + " sources");
  }
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::string& s = sources[i];
    if (options_.loop && VideoReader::IsLive(s)) {
      throw Error(s + ": a live source cannot loop (only video files start again)");
    }
    Source source;
    source.name = s;
    source.live = VideoReader::IsLive(s);
    source.reader = std::make_unique<VideoReader>(s);
    source.info = source.reader->info();
    if (!clocks.empty()) source.clock = clocks[i];
    sources_.push_back(std::move(source));
  }
  double fastest = 0.0;
  for (const Source& s : sources_) fastest = std::max(fastest, s.info.fps);
  tolerance_ = FromSeconds(0.5 / (fastest > 0 ? fastest : 30.0));
}

FrameSetReader::~FrameSetReader() = default;

void FrameSetReader::Lost(Source* s, const std::string& reason) {
  s->has_frame = false;
  s->reader.reset();
  s->lost_at = std::chrono::steady_clock::now();
  s->reconnect =
      std::make_unique<Reconnector>(s->name, options_.reconnect_min_s, options_.reconnect_max_s);
  // The reason without the source's name (the event names it).
  std::string why = reason.empty() ? "the stream ended" : reason;
  if (why.rfind(s->name + ": ", 0) == 0) why.erase(0, s->name.size() + 2);
  events_.push_back({static_cast<int>(s - sources_.data()), false, 0.0, why});
}

bool FrameSetReader::Reconnecting() const {
  return std::any_of(sources_.begin(), sources_.end(),
                     [](const Source& s) { return s.reconnect != nullptr; });
}

bool FrameSetReader::ReadAll() {
  bool any = false;
  for (Source& s : sources_) {
    if (s.reconnect) {
      std::unique_ptr<VideoReader> back = s.reconnect->Take();
      if (!back) continue;
      s.reconnect.reset();
      s.reader = std::move(back);
      s.rebase = true;
      s.consumed = true;
      events_.push_back(
          {static_cast<int>(&s - sources_.data()), true,
           std::chrono::duration<double>(std::chrono::steady_clock::now() - s.lost_at).count(),
           ""});
    }
    if (s.consumed && !s.ended) {
      std::string failure;
      try {
        s.has_frame = s.reader->ReadView(&s.view, &s.pts);
        if (!s.has_frame) failure = s.reader->ended_with();
      } catch (const Error& e) {
        // One source's failure ends that source, never the run.
        failure = e.what();
        s.has_frame = false;
      }
      for (const VideoGap& g : s.reader->TakeGaps()) {
        gaps_.push_back({static_cast<int>(&s - sources_.data()), g});
      }
      if (!s.has_frame && s.live && options_.reconnect) {
        Lost(&s, failure);
        continue;
      }
      if (!s.has_frame && !failure.empty()) errors_.push_back(failure);
      if (s.has_frame) {
        const auto now = std::chrono::steady_clock::now();
        if (!first_wall_) first_wall_ = now;
        s.pts = s.clock.WorldTime(s.pts) + shift_;
        if (s.rebase) {
          // A new stream's times start again: its first frame is placed at the wall clock's time
          // since the run's first frame.
          const TimeNs wall =
              first_pts_ +
              std::chrono::duration_cast<std::chrono::nanoseconds>(now - *first_wall_).count();
          s.live_shift = std::max(wall, last_pts_ + 1) - s.pts;
          s.rebase = false;
        }
        s.pts += s.live_shift;
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

std::vector<SourceEvent> FrameSetReader::TakeSourceEvents() { return std::exchange(events_, {}); }

std::vector<SourceGap> FrameSetReader::TakeGaps() { return std::exchange(gaps_, {}); }

bool FrameSetReader::StartAgain() {
  if (!options_.loop || !any_frame_) return false;
  double fps = 0.0;
  for (Source& s : sources_) {
    s.reader = std::make_unique<VideoReader>(s.name);
    s.reconnect.reset();
    s.has_frame = false;
    s.consumed = true;
    s.ended = false;
    fps = std::max(fps, s.info.fps);
  }
  // The next pass starts one frame period after the last frame of this one.
  const TimeNs period = FromSeconds(1.0 / (fps > 0 ? fps : 30.0));
  // (first_pts_ is the first pass's first frame: the files' own start.)
  shift_ = last_pts_ + period - first_pts_;
  ++loops_;
  return true;
}

bool FrameSetReader::Next(FrameSet* set) {
  // Nothing to read while a live source is away: wait for it (or for the stop).
  while (!ReadAll() && !(StartAgain() && ReadAll())) {
    if (!Reconnecting() || (options_.stop && options_.stop->load())) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
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
