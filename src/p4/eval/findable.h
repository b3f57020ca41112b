// How often the ball could be found at all: a ceiling for recall with a physical meaning (beyond
// the paper). In each camera's picture the streak search (segment/streak_search.h) is given the
// ball's TRUE centre, image motion over the exposure and size: a frame of a camera counts as
// findable when the search then finds the ball (its blend with the background stands out of the
// picture's own clutter along the true path). A frame seen by min_views cameras is findable when
// min_views of them find it. The tracker, which must find the ball without knowing where it is,
// can hardly do better where the ball's own pixels do not stand out (an orange ball over an
// orange floor, a 3 px ball over a shirt of its colour, a faint streak in H.264 at a low rate):
// a scene's recall is read against this share.
//
// Beside it, what a search with no prediction gets: a findable frame counts as started in a
// camera when the whole-image streak finder (segment/streak_finder.h, as the tracker runs it
// with no track) has a candidate within finder_match_px of the ball's true centre, and a frame as
// startable when min_views cameras start it. A track can start only there (or from the colour
// tables' regions): the share tells what the finder's own rules (its score, its "still" test, its
// candidate count) lose of what the search finds.
//
// Frames are matched to the truth by their stamps (cameras in step; within 0.5 ms of a truth
// row). The background model of each camera learns from every frame (BackgroundModel's warm-up
// frames are never findable). World frame, metres; pixels with centres at integers. Pure: the
// caller decodes the pictures.
#pragma once

#include <vector>

#include "p4/core/image.h"
#include "p4/core/time.h"
#include "p4/geometry/rig.h"
#include "p4/io/run_files.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/streak_finder.h"
#include "p4/segment/streak_search.h"

namespace p4 {

struct FindableOptions {
  double min_visibility = 0.5;  // share of the ball a camera sees for the frame to count there
  int min_views = 2;            // cameras that must see (and find) the ball
  segment::StreakSearchOptions search;
  // The short-term model alone (the default), as the tracker's streak search has it.
  segment::BackgroundOptions background;
  segment::StreakFinderOptions finder;  // as the tracker's (FrameSetOptions::streak_finder)
  // A candidate's middle is a cell's centre on a segment of whole cells: within this of the
  // ball's true centre, or half its own length, whichever is more, it is the ball.
  double finder_match_px = 8.0;
};

struct FindableReport {
  int frames_seen = 0;       // in play and seen by min_views cameras or more
  int frames_findable = 0;   // of those, found at the true place by min_views cameras or more
  int frames_startable = 0;  // of the findable, found by the whole-image finder in min_views
  std::vector<int> camera_seen, camera_found;  // per camera, over the frames it sees
  std::vector<int> camera_started;             // per camera, of the found: by the finder too
  double share() const {
    return frames_seen > 0 ? static_cast<double>(frames_findable) / frames_seen : 0.0;
  }
  double startable_share() const {
    return frames_seen > 0 ? static_cast<double>(frames_startable) / frames_seen : 0.0;
  }
};

class FindableCounter {
 public:
  // `visibility`: per truth row and camera, the share seen (ReadVisibilityCsv; empty: all seen).
  // `exposure_s`: the cameras' exposure (the streak's length is the image motion over it).
  FindableCounter(const Rig& rig, std::vector<TruthRow> truth,
                  std::vector<std::vector<float>> visibility, const segment::BallColour& ball,
                  double exposure_s, const FindableOptions& options = {});

  // Camera c's next picture, stamped t (each camera's pictures in time order).
  void Add(int camera, TimeNs t, const ImageView& image);
  FindableReport Report() const;

 private:
  bool Seen(std::size_t row, int camera) const;

  Rig rig_;
  std::vector<TruthRow> truth_;
  std::vector<std::vector<float>> visibility_;
  segment::BallColour ball_;
  double exposure_s_;
  FindableOptions options_;
  std::vector<segment::BackgroundModel> backgrounds_;
  std::vector<segment::StreakSearch> searches_;
  std::vector<segment::StreakFinder> finders_;
  std::vector<segment::StreakCandidate> candidates_;
  // Per truth row and camera: 1 found by the search, 2 by the finder as well.
  std::vector<std::vector<char>> found_;
};

}  // namespace p4
