// The clocks of a rig's cameras from the ball's motion (beyond the paper): every camera's 2D
// tracks (track_2d.h) against the first camera's, whose clock is the rig's (offset_search.h).
// Pure: the frames' candidates come in, the clocks go out.
#pragma once

#include <vector>

#include "p4/geometry/rig.h"
#include "p4/sync/offset_search.h"
#include "p4/sync/track_2d.h"

namespace p4::sync {

struct RigSyncOptions {
  Track2dOptions tracks;
  OffsetOptions offsets;

  bool IsValid(std::string* error) const { return tracks.IsValid(error) && offsets.IsValid(error); }
};

struct RigSyncResult {
  Rig rig;                            // the input rig with every camera's clock found
  std::vector<OffsetResult> cameras;  // per camera (the first: the reference, found = true)
  std::vector<int> tracks;            // 2D tracks per camera
  bool all_found = false;
};

// `frames[c]`: camera c's frames (stamps in its own clock, top row). Rows' delays are added from
// each camera's line_time_s; the first camera's offset and rate are kept as the rig has them.
// Cameras whose offset cannot be found keep their clock, and their result says why.
RigSyncResult SynchroniseRig(const Rig& rig,
                             const std::vector<std::vector<FrameCandidates>>& frames,
                             const RigSyncOptions& options = {});

}  // namespace p4::sync
