// Finding a faint blur streak where the filter expects the ball (beyond the paper: its cameras
// ran 1/1000 s exposures; webcams indoors expose 1/60-1/30 s).
//
// A ball of d px that crosses L px during the exposure leaves a streak in which no pixel is more
// than about d / (L + d) ball: at 10 m/s and 1/40 s a 4 px ball is 4 % of each pixel it touches,
// a few levels over the table, below any per-pixel or per-block threshold. Summed along the path
// the filter predicts, those few levels stand far above the noise (18 sigma on a 3 px ball in a
// 28 ms webcam frame). So: for segments near the predicted one (its centre shifted, its length
// and direction varied), sum every pixel's difference from the background projected on the
// difference the ball's colour would make there (a matched filter; luma per pixel, chroma per
// 2x2 block), and compare the best with the same template laid elsewhere in the picture (the
// picture's own clutter is the null, not a fixed threshold). What passes must also look like a
// streak: its mean share of the pixels is what a disc of d px smeared over its length gives, and
// the ring just outside it does not differ (an arm or a shirt fills both). Each hit says too
// whether the streak shows the ball's colour: its difference from the background summed over it
// and a margin (4:2:0 and the encoder smear a faint streak's chroma, but keep its sum), unmixed
// as the ball at any shading (ball_colour.h). Skin lightening a brown floor fits no positive
// share of an orange ball; the caller judges (track::FrameSetOptions::off_colour_residual).
//
// Measured (foreground_scene_test.cc): 50 px streaks of a 5 px ball at 640x360, each pixel under
// a tenth ball, found in 12 of 12 frames (the block regions: 4), 10 within 0.75 px of the exact
// centre, 23-63 sigmas; nothing in 12 frames without the ball. 2.2 ms a search at 640x480
// (p4_micro_bench, BM_StreakSearch).
//
// Pixel coordinates: centres at integers; the segment joins the ball's centres at the start and
// the end of the exposure, so its middle is the ball at mid-exposure. Pure: buffers are kept.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"

namespace p4::segment {

struct StreakSearchOptions {
  double search_px = 8.0;       // the segment's middle is looked for within this of the predicted
  double coarse_step_px = 2.0;  // first pass (whole pixels), then quarter steps around the best
  // Lengths tried, as shares of max_length_px (the exposure is unknown up to the frame period).
  std::vector<double> length_shares = {0.15, 0.3, 0.5, 0.75, 1.0};
  int angles = 5;               // directions tried about the predicted one...
  double angle_step_px = 1.5;   // ...each turning the streak's end by this many pixels
  double min_snr = 8.0;         // the best over the null's robust spread
  int null_samples = 48;        // the same template laid elsewhere in the null window
  double null_reach_px = 60.0;  // half-size of the null window
  // The streak's mean share of its pixels over what the disc smeared along it would give.
  double min_share_ratio = 0.35, max_share_ratio = 2.5;
  // A pixel counts as at most this many times the streak's mean share (clutter beside or across
  // the streak, a player or a line, must not pull the template onto it).
  double max_pixel_share = 3.0;
  double max_ring_ratio = 0.5;  // the ring outside: at most this share of the streak's mean share
  double shade = 0.85;          // the ball's mean shading over its disc (1: all lit)
  double min_contrast = 6.0;    // levels: pixels where the ball would differ less do not count
  double chroma_weight = 2.0;   // as UnmixOptions

  bool IsValid(std::string* error) const;
};

struct StreakHit {
  double cx = 0.0, cy = 0.0;  // the segment's middle (the ball at mid-exposure), px
  double length_px = 0.0;     // the segment's length (centre travel over the exposure)
  double angle = 0.0;         // its direction, radians from the image x axis
  double snr = 0.0;           // over the null's robust spread
  double share = 0.0;         // mean share of the ball in the streak's pixels
  double expected_share = 0.0;
  double ring_share = 0.0;
  // The streak's summed difference from the background unmixed as the ball (ball_colour.h):
  // the residual over the difference (0: the ball's colour at some shading, 1: none of it).
  double colour_residual = 0.0;
};

class StreakSearch {
 public:
  // The streak of a ball of `diameter_px` nearest the predicted one: its middle near (mid_x,
  // mid_y), its direction near (dir_x, dir_y), its length (the centre's travel over the
  // exposure) at most max_length_px (the predicted travel over a whole frame period: the exposure
  // is some unknown part of it). The middle and the length come from the moments of the streak's
  // shares along it (L^2 / 12 + d^2 / 16). Nullopt when nothing stands out of the picture's
  // clutter by min_snr, or what does is no streak (its share or its ring). Precondition: the
  // background is ready and has the image's size.
  std::optional<StreakHit> Find(const ImageView& image, const BackgroundModel& background,
                                const BallColour& ball, double mid_x, double mid_y, double dir_x,
                                double dir_y, double max_length_px, double diameter_px,
                                const StreakSearchOptions& options);

 private:
  struct Sums {
    double m = 0.0, e = 0.0;  // sum of projected differences, sum of squared expected ones
    int n = 0;
  };
  // Sums over the pixels within `inner`..`outer` of the segment (inner < 0: from its line).
  // Each pixel's difference counts up to `clip` times its expected energy (a share of the ball).
  Sums Template(double cx, double cy, double ux, double uy, double length, double inner,
                double outer, double clip) const;
  // StreakHit::colour_residual of a hit.
  double ColourResidual(const ImageView& image, const BackgroundModel& background,
                        const BallColour& ball, const StreakHit& hit, double diameter_px,
                        const StreakSearchOptions& options) const;
  double Score(const Sums& s) const { return s.e > 0.0 ? s.m / std::sqrt(s.e) : 0.0; }
  // The same over whole pixels: the template at an integer middle as a list of offsets into the
  // window (BuildShape), for the coarse search and the null.
  void BuildShape(double ux, double uy, double length, double radius);
  Sums ShapeSums(int cx, int cy, double clip) const;
  std::vector<std::ptrdiff_t> shape_;
  int shape_x0_ = 0, shape_y0_ = 0, shape_x1_ = 0, shape_y1_ = 0;

  // The window's per-pixel matched difference m = d . c and expected energy e = c . c.
  int x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
  std::vector<float> m_, e_;
  std::vector<double> null_;
};

}  // namespace p4::segment
