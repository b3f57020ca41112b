// Faint blur streaks anywhere in the picture, with no prediction (beyond the paper: its cameras
// ran 1/1000 s exposures; a webcam's 1/30 s leaves a fast ball a streak a few levels over the
// table, which no colour table and no per-block threshold finds, so no track could start).
//
// The coarse stage of StreakSearch (streak_search.h) for the whole image: every 2x2 block's
// difference from the background is projected on the difference the ball's colour would make
// there (a matched filter), each block counted up to `max_share` of the ball (a player counts as
// a faint streak would, no more), and summed into cells of 4x4 pixels (a line one cell wide holds
// a ball of 3-6 px). These are summed along segments of 8 directions and a few lengths (prefix
// sums along the lines of each direction: a segment costs two look-ups) and compared with the
// same sums on the two lines beside it, `side_cells` away: a streak is a thin line, a player or
// an arm fills the sides too. A segment's score is its excess over the brighter side, in sigmas
// of the blocks' noise (BackgroundModel). The best segments apart from one another are the
// candidates, but none where one was in the last frame (a lamp, a line or a player's edge stays,
// the ball in play never leaves two streaks at one place) unless the hall around it is as the
// background has it (the ball near the top of a toss moves less than a cell a frame; a player's
// speck or edge has the player around it). StreakSearch then measures each against the
// picture's own clutter.
//
// Measured (foreground_scene_test.cc): the 45-65 px streaks of a 5 px ball (each pixel under a
// tenth ball) found with no prediction in 11 of 12 frames, 9 within 1.5 px; without the ball,
// 10 short strips on the players (12-30 px) pass in 12 frames. 5-8 ms at 640x480
// (p4_micro_bench, BM_StreakFinder).
//
// Pixel coordinates: centres at integers. Pure: buffers and the last frame's candidates are kept
// between calls (one finder per camera).
#pragma once

#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/streak_search.h"

namespace p4::segment {

struct StreakFinderOptions {
  // The lines run over cells of cell_blocks x cell_blocks blocks (4x4 px: a line one cell wide
  // holds a ball of 3-6 px).
  int cell_blocks = 2;
  // Half-lengths tried, in cells along the line's major axis (a segment spans 2h + 1 cells):
  // 12-68 px streaks, a ball crossing a webcam's frame at 3-15 m/s.
  std::vector<int> half_cells = {1, 2, 4, 8};
  int side_cells = 2;       // the side lines' offset across the segment, cells
  double max_share = 0.35;  // a block counts as at most this much ball
  double min_score = 5.0;   // sigmas over the brighter side
  // The best, apart from one another by their half-lengths... (arms and shirts' edges of the
  // ball's colour outscore a faint ball and took every place of 4: in webcam tuning 4, camera
  // 0, the ball was among the best 4 in 79 of 155 frames, among 8 in 90, among 16 in 91)
  int max_candidates = 8;
  double still_px = 4.0;  // ...and from where one was in the last frame (the ball moves),
  // unless it stands alone in the hall: of the blocks whose centres lie isolated_inner_px to
  // isolated_outer_px from its segment, at most isolated_max_share differ from the background
  // (by its foreground sigmas). At 25 fps the ball at the top of a toss moves 2-4 px a frame,
  // within still_px (the candidates' middles lie on the cells' 4 px grid); a speck of a player,
  // the edge of a shirt or a shoulder has the player around it. (In webcam tuning 4 the still
  // test dropped the ball in 46 of the 76 findable camera-frames the finder missed.) Negative
  // isolated_max_share: none is kept.
  double isolated_inner_px = 4.0;
  double isolated_outer_px = 12.0;
  double isolated_max_share = 0.05;
  int max_seen = 32;           // local bests remembered for the next frame
  double shade = 0.85;         // the ball's mean shading (as StreakSearchOptions)
  double min_contrast = 6.0;   // levels: blocks where the ball would differ less do not count
  double chroma_weight = 2.0;  // as UnmixOptions

  bool IsValid(std::string* error) const;
};

struct StreakCandidate {
  double cx = 0.0, cy = 0.0;  // the segment's middle, px
  double angle = 0.0;         // its direction, radians from the image x axis, in [0, pi)
  double length_px = 0.0;     // its length, px
  double score = 0.0;         // sigmas over the brighter side line
};

class StreakFinder {
 public:
  // The best candidates in the picture, best first, none where one was in the last call's
  // picture but those that stand alone (call once per frame of one camera); returns their number.
  // Precondition: the background is ready and has the image's size.
  int Find(const ImageView& image, const BackgroundModel& background, const BallColour& ball,
           const StreakFinderOptions& options, std::vector<StreakCandidate>* out);

 private:
  int bw_ = 0, bh_ = 0;
  std::vector<float> m_, v_;            // per cell: clipped matched difference, its noise variance
  std::vector<float> pm_, pv_;          // per cell: prefix sums along the current direction's lines
  std::vector<float> line_m_, line_v_;  // one step t: each line's segment sums...
  std::vector<float> score_;            // ...and score
  std::vector<int> step_;               // the current direction's step at t - 1, t = 0..
  std::vector<float> best_;             // per cell: the best score so far, squared
  std::vector<int> best_dir_, best_half_;
  std::vector<StreakCandidate> last_seen_;  // the last frame's local bests
};

// A faint streak found with no prediction, measured.
struct FoundStreak {
  StreakHit hit;             // measured by StreakSearch about the finder's candidate
  double diameter_px = 0.0;  // the ball's, from the streak's share of its pixels
};

// The whole picture's faint streaks: the finder's candidates (above) longer than two of the
// ball's expected diameters (a shorter one is no faint streak: the colour regions find that
// ball), each measured by the search about the candidate (its middle within a cell, its length
// at most 1.5 times the candidate's). A disc of d px smeared along a streak shares about d^2 of a
// template d0 wide, so d = d0 sqrt(share / expected share). Returns their number, best first.
// Preconditions as StreakFinder::Find; `diameter_px` > 0.
int FindStreaks(const ImageView& image, const BackgroundModel& background, const BallColour& ball,
                double diameter_px, const StreakFinderOptions& finder_options,
                const StreakSearchOptions& search_options, StreakFinder* finder,
                StreakSearch* search, std::vector<FoundStreak>* out);

}  // namespace p4::segment
