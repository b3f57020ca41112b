// Each source's ball candidates, frame by frame, read on its own (beyond the paper: before the
// cameras' clocks are known there are no frame sets). The colour tables over the whole picture
// (paper §3.1) where it differs from a background model learnt as the frames come (with
// segment::AnyColour(), whatever moves), regions of the ball's size for the camera (nearer than
// 1 m is too big, a few pixels across is the least) that were not in the last frame, their
// centroids; with a camera of 40 fps or slower, the middles of faint streaks too. Hands and heads
// that pass make 2D tracks too: any real moving thing that both cameras see tells their offset. For
// sync/rig_sync.h.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "p4/geometry/rig.h"
#include "p4/io/color_class_file.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/color_classes.h"
#include "p4/sync/rig_sync.h"
#include "p4/sync/track_2d.h"

namespace p4 {

struct BallCandidateOptions {
  double seconds = 15.0;  // from each source's start
  int per_frame = 6;      // the largest regions of the ball's size
  double min_diameter_px = 1.5;
  // A blurred ball is a streak no longer than its width plus its path over a whole frame (a
  // webcam's exposure can last the frame) at the fastest image speed (sync::Track2dOptions').
  double max_speed_px_s = 4000.0;
  double still_px = 1.5;       // a region this near one of the last frame's did not move: dropped
  double moving_sigmas = 3.0;  // pixels must differ from the learnt background by this much
  // Cameras this slow or slower also give the faint streaks anywhere in the picture
  // (segment::FindStreaks, as the tracker's --streaks auto): a webcam's exposure of 1/60-1/30 s
  // leaves a fast ball a streak that no colour region finds, and then too few of the ball's
  // views for the offset. They come beside the per_frame regions (up to the finder's 8), not in
  // their places. 0: never.
  double streak_max_fps = 40.0;
  segment::BallColour ball;  // the streaks' colour (SyncBallOf)

  bool IsValid(std::string* error) const;
};

// Reads the first `seconds` of every source (a thread each; files only) and returns, per source,
// its frames' candidates with the file's own stamps. Throws p4::Error naming a source that
// cannot be read or whose size differs from its rig camera's.
std::vector<std::vector<sync::FrameCandidates>> ReadBallCandidates(
    const Rig& rig, const std::vector<std::string>& sources, const segment::ColorClassSet& classes,
    const BallCandidateOptions& options = {});

// The rig's clocks from the sources: their candidates (above), then sync::SynchroniseRig.
sync::RigSyncResult SyncFromSources(const Rig& rig, const std::vector<std::string>& sources,
                                    const segment::ColorClassSet& classes,
                                    const BallCandidateOptions& candidates = {},
                                    const sync::RigSyncOptions& sync = {});

// One line on a camera's clock as found: "cam1: +0.123412 s +- 0.03 ms (...)" or why not.
std::string DescribeClock(const Camera& camera, const sync::OffsetResult& result, bool reference);

// The ball the sync looks for (`p4track sync`, and `track` before it syncs): a classes file's
// classes, and its lit colour (ball_lit, which a run that learnt the colour saves) for the faint
// streaks; without a file the hint's (`hint` auto or any: any colour, the streaks an orange
// ball's).
struct SyncBall {
  segment::ColorClassSet classes;
  segment::BallColour streak;
};
SyncBall SyncBallOf(const std::optional<ColorClassFile>& file, const std::string& hint);

}  // namespace p4
