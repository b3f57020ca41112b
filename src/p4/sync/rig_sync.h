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
  // Gaps are at least min_gap_frames of the camera's own frame period (its median stamp step):
  // a 25 fps webcam that misses one frame leaves 80 ms, more than a 60 fps camera's 50 ms.
  Track2dOptions tracks;
  OffsetOptions offsets;
  double min_gap_frames = 2.5;

  bool IsValid(std::string* error) const {
    if (!(min_gap_frames >= 1.0)) {
      if (error) *error = "sync: min_gap_frames must be at least 1";
      return false;
    }
    return tracks.IsValid(error) && offsets.IsValid(error);
  }
};

struct RigSyncResult {
  Rig rig;                            // the input rig with every camera's clock found
  std::vector<OffsetResult> cameras;  // per camera (the first: the reference, found = true)
  std::vector<int> tracks;            // 2D tracks per camera
  bool all_found = false;
};

// `frames[c]`: camera c's frames (stamps in its own clock, top row). Rows' delays are added from
// each camera's line_time_s; the first camera's offset and rate are kept as the rig has them.
// Cameras whose offset cannot be found keep their clock, and their result says why. With
// options.offsets.fit_line_times every camera's line time is found too (added to the rig's; the
// reference's is the mean of what each camera's pair found).
RigSyncResult SynchroniseRig(const Rig& rig,
                             const std::vector<std::vector<FrameCandidates>>& frames,
                             const RigSyncOptions& options = {});

}  // namespace p4::sync
