// Holds the frame-set tracker's results back long enough for later ones to revise them: a
// tracklet confirmed at t (track_initiator.h) makes measurements of the ball out of the tentative
// candidates of the time-stamps before it. A result leaves after hold_s of time-stamps (or on
// Flush); one still tentative then is not the ball: its measurement is dropped.
//
// Time-stamps in ns from the results; pure.
#pragma once

#include <deque>
#include <vector>

#include "p4/track/frame_set_tracker.h"

namespace p4::track {

class ResultHold {
 public:
  // hold_s >= the initiator's max_span_s loses no revision.
  explicit ResultHold(double hold_s);

  // Takes a result (time-stamps increasing), applies its revisions to the held ones; returns the
  // results now final, oldest first.
  std::vector<FrameSetResult> Push(FrameSetResult result);
  // Every held result, final, after `revisions` (the tracker's last: FrameSetTracker::Finish).
  std::vector<FrameSetResult> Flush(const std::vector<Revision>& revisions = {});

  int revised() const { return revised_; }  // time-stamps a revision reached
  int missed() const { return missed_; }    // revisions that came after their time-stamp left

 private:
  static FrameSetResult Final(FrameSetResult result);
  void Apply(const std::vector<Revision>& revisions);

  TimeNs hold_;
  std::deque<FrameSetResult> held_;
  int revised_ = 0;
  int missed_ = 0;
};

}  // namespace p4::track
