// `p4track track` as a library call: frame sets from the sources, the per-time-stamp tracker,
// the run's files written as it goes, and a summary. The edge between the pure tracker and the
// files and clocks.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "p4/geometry/rig.h"
#include "p4/segment/color_classes.h"
#include "p4/track/frame_set_tracker.h"

namespace p4 {

struct TrackRunSummary {
  int64_t frame_sets = 0;
  int64_t measured = 0;    // time-stamps with a 3D measurement
  int64_t multi_view = 0;  // of which triangulated from >= 2 cameras
  int64_t states = 0;      // rows in trajectory.csv
  int64_t roi_hits = 0;    // camera searches that found the ball in their window
  int64_t roi_searches = 0;
  double video_seconds = 0.0;  // time span of the frame sets
  double wall_seconds = 0.0;
  std::vector<std::string> sources_ended_with_error;  // live sources that failed mid-run
  double measurements_per_second() const {
    return wall_seconds > 0 ? measured / wall_seconds : 0.0;
  }
  std::string Report() const;
};

// Checks sources against the rig (count, image sizes) and runs. `progress` (may be empty) is
// called about twice a second with the frame sets done. Throws p4::Error with the source or
// field at fault.
TrackRunSummary RunTracking(const Rig& rig, const segment::ColorClassSet& classes,
                            const std::vector<std::string>& sources, const std::string& out_dir,
                            const track::FrameSetOptions& options,
                            const std::function<void(int64_t)>& progress);

}  // namespace p4
