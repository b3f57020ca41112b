// The ball's path in one camera's pictures, before any 3D (beyond the paper: cameras out of step
// are synchronised from these paths, sync/offset_search.h). Each frame's candidates (centres of
// ball-coloured regions) are linked into tracks by nearest neighbour under a constant-velocity
// prediction; what does not travel (lamps, lettering, a ball lying on the floor) or does not last
// is dropped.
//
// Times are seconds in the camera's own clock (its file's timestamps); pixels as everywhere
// (centres at integers, the camera's real, distorted image). Pure.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace p4::sync {

// One frame's candidates.
struct FrameCandidates {
  double t = 0.0;  // stamp, seconds (the top row's exposure)
  std::vector<Eigen::Vector2d> pixels;
};

struct TrackPoint {
  double t = 0.0;  // stamp, seconds
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};

// Consecutive detections of one moving thing, in time order.
struct Track2d {
  std::vector<TrackPoint> points;
};

struct Track2dOptions {
  double max_speed_px_s = 4000.0;  // a link may not be faster (a smash at 3 m from a 1000 px lens)
  double gate_px = 4.0;            // plus this around the constant-velocity prediction
  double gate_speed_share = 0.35;  // plus this share of the predicted step (bounces, hits)
  double max_gap_s = 0.05;         // a track waits this long for its next point
  int min_points = 6;              // a kept track has this many points...
  double min_travel_px = 15.0;     // ...and its ends lie this far apart

  bool IsValid(std::string* error) const;
};

// Links the frames' candidates (in time order) into tracks of moving things.
std::vector<Track2d> LinkTracks(const std::vector<FrameCandidates>& frames,
                                const Track2dOptions& options = {});

// A camera's frame period: the median step between consecutive stamps of its frames, or of the
// points within its tracks (seconds; 0 with no step).
double FramePeriod(const std::vector<FrameCandidates>& frames);
double FramePeriod(const std::vector<Track2d>& tracks);

}  // namespace p4::sync
