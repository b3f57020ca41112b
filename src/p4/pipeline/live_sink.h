// What a live view receives from the tracking loop (paper Figure 6: every camera with its ROI,
// the epipolar lines and the ball, above the 3D view). The loop calls it after every frame set;
// an implementation must return at once (copy what it needs, drop what it cannot keep up with):
// tracking never waits for a viewer.
#pragma once

#include <span>

#include "p4/game/event.h"
#include "p4/game/match_score.h"
#include "p4/pipeline/frame_set_reader.h"
#include "p4/track/frame_set_tracker.h"

namespace p4 {

class LiveSink {
 public:
  virtual ~LiveSink() = default;
  // `set`'s image views are valid during the call only. `events`: the events published by this
  // frame set (detected and the referee's); `score` is null without a referee.
  virtual void OnFrameSet(const FrameSet& set, const track::FrameSetResult& result,
                          std::span<const game::Event> events, const game::MatchScore* score) = 0;
  // A live source lost (being opened again) or back (FrameSetReader), before the next frame set.
  virtual void OnSourceEvent(const SourceEvent& /*event*/) {}
};

}  // namespace p4
