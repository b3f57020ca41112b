#include "p4/track/result_hold.h"

#include <algorithm>

namespace p4::track {

ResultHold::ResultHold(double hold_s) : hold_(FromSeconds(std::max(0.0, hold_s))) {}

FrameSetResult ResultHold::Final(FrameSetResult result) {
  if (result.tentative) {
    result.measurement.reset();
    result.tentative = false;
    if (result.state) {
      result.state->measured = false;
      result.state->cameras = 0;
      result.state->residual_px = 0.0;
    }
  }
  return result;
}

void ResultHold::Apply(const std::vector<Revision>& revisions) {
  for (const Revision& r : revisions) {
    const auto it = std::find_if(held_.begin(), held_.end(),
                                 [&](const FrameSetResult& h) { return h.t == r.t; });
    if (it == held_.end()) {
      ++missed_;
      continue;
    }
    ++revised_;
    if (r.drop) {
      it->state.reset();
      continue;
    }
    if (r.not_ball) {
      ClearMeasurement(&*it);
      it->state.reset();
      it->tentative = false;
      continue;
    }
    it->measurement = r.measurement;
    it->state = r.state;
    it->tentative = false;
    for (auto& d : it->detections) d.accepted = false;
    for (int i : r.accepted) {
      if (i >= 0 && i < static_cast<int>(it->detections.size())) it->detections[i].accepted = true;
    }
  }
}

std::vector<FrameSetResult> ResultHold::Push(FrameSetResult result) {
  Apply(result.revisions);
  result.revisions.clear();
  const TimeNs newest = result.t;
  held_.push_back(std::move(result));
  std::vector<FrameSetResult> out;
  while (!held_.empty() && newest - held_.front().t > hold_) {
    out.push_back(Final(std::move(held_.front())));
    held_.pop_front();
  }
  return out;
}

std::vector<FrameSetResult> ResultHold::Flush(const std::vector<Revision>& revisions) {
  Apply(revisions);
  std::vector<FrameSetResult> out;
  for (auto& r : held_) out.push_back(Final(std::move(r)));
  held_.clear();
  return out;
}

}  // namespace p4::track
