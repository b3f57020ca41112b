// Finding the ball as what differs from the background AND has the ball's colour mixed with that
// background (beyond the paper; its run-length rows and union-find, §3.1, at block resolution).
//
// 1. Blocks (2x2 pixels, the chroma's resolution) that differ from the BackgroundModel by more
//    than its foreground bound and whose colour unmixes as the ball over their background
//    (ball_colour.h: any shading, any share of the block) are run-length encoded per block row
//    and joined into regions by union-find.
// 2. Each region is measured at full resolution by coverage: every pixel's share of the ball,
//    from its luma between the background's and the ball's at the local shading (from the
//    block's chroma where the luma says too little). The coverage-weighted centre is the ball's
//    centre at mid-exposure, not its lit half; the coverage sum is the disc's area whatever the
//    motion blur; the weighted moments give the streak's direction and length (the ball's image
//    speed over the exposure).
// 3. A ball of known size joined to something of its colour that also differs (a line, a sleeve)
//    is found as the disc of that size which stands out of its ring (FindDisc).
//
// Pixel coordinates: centres at integers. Pure: buffers are kept between calls.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/blob_finder.h"
#include "p4/segment/color_classes.h"

namespace p4::segment {

struct ForegroundOptions {
  double min_alpha = 0.12;  // a block must be at least this much ball
  double max_alpha = 1.6;
  double max_residual_share = 0.3;  // residual <= this share of the block's difference...
  double residual_sigmas = 3.0;     // ...or within this many of the block's noise
  double min_luma_contrast = 12.0;  // below it a pixel's coverage comes from its block's colour
  double interior_alpha = 0.9;      // a block this much ball is inside it: its pixels count whole
  double own_shade_alpha = 0.3;     // a block this much ball uses its own shading, the others the
                                    // region's (share-weighted: a blur streak's are all faint)
  int max_regions = 16;
  // Shapes that are not a ball, even blurred: too large, or longer than this times their width.
  int max_blocks = 1500;
  double max_elongation = 8.0;
  // The ball's size range in this camera (the tracker sets it from the focal length: no nearer
  // than about a metre); regions outside it are not kept.
  double min_diameter_px = 1.5, max_diameter_px = 60.0;
  // A round region (major < core_max_elongation x minor: not a blur streak) with at least
  // core_min_pixels pixels covered by >= core_alpha, in blocks whose colour is >= core_alpha
  // ball, must show the ball's colour in these colour classes (the paper's tables) for at least
  // core_share of them: skin or a shirt unmixes as a shaded ball, the tables tell them apart (a
  // small blurred ball, whose chroma is mostly the background's, is not judged). Null: no check.
  const ColorLut* lut = nullptr;
  uint32_t lut_mask = 0xffffffffu;
  double core_alpha = 0.5, core_share = 0.2, core_max_elongation = 2.0;
  int core_min_pixels = 4;
  UnmixOptions unmix;

  bool IsValid(std::string* error) const;
};

// A region found on the background, measured by coverage.
struct CoverageRegion {
  Region region;              // cx, cy coverage-weighted; area = coverage sum (rounded); diameters
                              // from the coverage: diameter = 2 sqrt(coverage / pi), minor/major
                              // from the weighted moments
  double coverage = 0.0;      // sum of the pixels' ball shares, px^2 (the disc's area)
  double shade = 1.0;         // its blocks' shading weighted by share (1: the lit colour)
  double streak_px = 0.0;     // length of the motion-blur streak along the major axis, px
  double streak_angle = 0.0;  // its direction, radians from the image x axis
  int blocks = 0;
  double roundness = 0.0;  // coverage / area of the ellipse of its moments (1 for a disc)
};

// A ball of known size inside a larger region of its colour (FindDisc).
struct DiscSearchOptions {
  // The ring about the disc that must be less ball than the disc: this share of the diameter
  // wide, at least min_ring_px.
  double ring_share = 0.4;
  double min_ring_px = 2.0;
  double min_fill = 0.6;       // the disc's pixels are on average at least this much ball...
  double min_contrast = 0.45;  // ...and this much more than the ring's
  int refine_iterations = 3;   // centre by the coverage within the disc, this many times

  bool IsValid(std::string* error) const;
};

class ForegroundFinder {
 public:
  // Regions inside `roi` (whole image when empty), the roundest first (a blurred ball is an
  // even streak; legs, arms and shirts are ragged); returns their number.
  // Precondition: the model is ready and has the image's size.
  int Find(const ImageView& image, const BackgroundModel& background, const BallColour& ball,
           const Roi& roi, const ForegroundOptions& options, std::vector<CoverageRegion>* out);

  // The blocks of `roi` (whole image when empty) that differ from the background by more than
  // `sigmas`, grown by one block unless `grow` is false, as a mask for BlobFinder (valid until
  // the next call; blocks outside the ROI's are left as they were). Precondition: the model has
  // the image's size.
  BlockMask DifferingBlocks(const ImageView& image, const BackgroundModel& background,
                            const Roi& roi, double sigmas, bool grow = true);

  // The share of the blocks of `roi` that differ from the background by more than `sigmas`
  // (0 for an empty ROI). Precondition: the model has the image's size.
  static double DifferingShare(const ImageView& image, const BackgroundModel& background,
                               const Roi& roi, double sigmas);

  // Every block of the image, but inside the `within` windows only the blocks that differ (as
  // DifferingBlocks): a colour region too large for the ball (a floor or banner of its colour,
  // which the ball over it joins) is searched again on what is not the hall, the rest as it was.
  // Only windows whose DifferingShare is at most `max_share` are masked (each window's blocks
  // compared once for both); they are appended to *taken when given. Valid until the next call.
  // Precondition: the model has the image's size.
  BlockMask DifferingBlocksWithin(const ImageView& image, const BackgroundModel& background,
                                  std::span<const Roi> within, double sigmas, bool grow = true,
                                  double max_share = 1.0, std::vector<Roi>* taken = nullptr);

  // Measures a window (e.g. a colour region's box grown by a margin) by coverage.
  // False when nothing in it is the ball.
  bool Measure(const ImageView& image, const BackgroundModel& background, const BallColour& ball,
               const Roi& window, const ForegroundOptions& options, CoverageRegion* out);

  // The ball, of known diameter, inside a larger region that differs from the background with
  // its colour (a ball that meets a line, an arm or a shirt's edge in the image): among the whole
  // pixel centres within search_px of (cx, cy) (every tenth of a diameter, for a ball of 20 px
  // and more), the disc of that diameter that is most ball
  // against a ring about it (a ball across a line has two thin crossings in its ring; one inside
  // a shirt has a full ring and is not found). Its centre is then the coverage-weighted centre of
  // the disc's pixels; out->coverage their sum, minor and major the disc's diameter, roundness
  // the disc's fill. False when no disc stands out (DiscSearchOptions). Precondition: the model
  // is ready and has the image's size; diameter_px > 0.
  bool FindDisc(const ImageView& image, const BackgroundModel& background, const BallColour& ball,
                double cx, double cy, double search_px, double diameter_px,
                const ForegroundOptions& options, const DiscSearchOptions& disc,
                CoverageRegion* out);

 private:
  std::vector<Run> runs_;
  // Per block of the window being measured: shading, share, kind, and whether it counts.
  std::vector<float> block_shade_, block_alpha_;
  std::vector<uint8_t> kind_, counts_;
  std::vector<float> alpha_;             // per pixel of the window being measured: the ball's share
  std::vector<uint8_t> mask_, differs_;  // DifferingBlocks: the mask and the blocks before growth
  // The 2x2 blocks [x0, x1) x [y0, y1) of the background model.
  struct BlockRange {
    int x0, y0, x1, y1;
    int size() const { return x1 > x0 && y1 > y0 ? (x1 - x0) * (y1 - y0) : 0; }
  };
  // The ball's share of every pixel of window `w` (even-aligned, inside the model) into alpha_
  // (rows of w's width; 0 where nothing of the ball is), with the blocks' buffers above; the
  // shading of the window's ball blocks weighted by share into *region_shade. False when no block
  // of the window is the ball.
  bool FillCoverage(const ImageView& image, const BackgroundModel& background,
                    const BallColour& ball, const Roi& w, const ForegroundOptions& options,
                    float* region_shade);
  // Pixels mostly ball (their own share and their block's at least core_alpha), and of those the
  // ones the colour tables call ball: a round region's core must show the ball's colour (skin
  // and shirts unmix as a shaded ball; the tables say no).
  struct CoreCount {
    int core = 0, in_tables = 0;
  };
  // Counts pixel (x, y) of window w (after FillCoverage), whose share is alpha.
  void CountCore(const ImageView& image, const ForegroundOptions& options, const Roi& w, int x,
                 int y, double alpha, CoreCount* count) const;
  // The tables refuse the core (with the tables, enough core pixels, too few of them in them).
  static bool CoreNotBall(const ForegroundOptions& options, const CoreCount& count);
  // The blocks a pixel ROI covers, inside the model's.
  static BlockRange BlocksOf(const Roi& roi, const BackgroundModel& background);
  // The blocks of `range` that differ from the background by more than `sigmas`, each written
  // to `out` (rows of background.width() / 2) when given; returns how many.
  static int CountDiffering(const ImageView& image, const BackgroundModel& background,
                            const BlockRange& range, double sigmas, uint8_t* out);
  // Writes differs_ over the blocks of `range` (both buffers sized to the model's blocks);
  // returns how many differ.
  int CompareBlocks(const ImageView& image, const BackgroundModel& background,
                    const BlockRange& range, double sigmas);
  // Writes mask_ over the blocks of `range`: those that differ, grown by one within the range.
  void GrowMask(const BackgroundModel& background, const BlockRange& range, bool grow);
};

}  // namespace p4::segment
