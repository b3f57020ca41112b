// The ball's centre from its edge (beyond the paper, whose centre is the colour region's
// centroid, §3.1). The colour tables take the part of the ball whose chroma the encoder left
// right (H.264 smears chroma over 4x4 and 8x8 blocks: half a small ball can carry the wall's
// chroma) and a luma-weighted centroid leans to the lit half; both move the centre by up to a
// pixel, which the epipolar check and the depth do not forgive.
//
// Rays from a first guess of the centre sample the colour (luma; chroma at a quarter weight, for
// a dark orange ball on a blue table that differs in chroma only). The background is the ring
// beyond the ball (per channel the median of the rays' ends; a ray ending on a line or a shadow
// takes the ring's colour). On each ray the edge is where the colour distance from the
// background has fallen to half of its value 1.5 px further in: the ball's shading changes the
// colour slowly inside the disc, so the dark half's edge is where its own level meets the
// background, and a line beyond the ball comes after the edge. A disc, an ellipse and a short
// blur streak are centrally symmetric, so the edges of opposite rays are as far from the true
// centre: half their difference, over all pairs, gives the centre's offset by least squares.
// Pairs that do not agree (a ray that ran into a line, a shadow, another ball) are dropped and
// the rays cast again from the new centre. For a disc or a short streak (up to about twice as
// long as wide: a long streak's ends are ramps whose crossings the noise moves).
//
// Pixel coordinates: centres at integers. Pure.
#pragma once

#include <optional>
#include <string>

#include "p4/core/image.h"

namespace p4::segment {

struct EdgeCentreOptions {
  int directions = 12;           // rays, in opposite pairs (even)
  double step_px = 0.75;         // sampling step along a ray
  double reach = 1.4;            // a ray runs to reach x the radius guess...
  double reach_margin_px = 2.5;  // ...plus this (the background beyond the edge)
  double min_contrast = 12.0;    // the ball's colour distance from the background, 8-bit levels
  double chroma_weight = 0.25;   // of U and V against Y in that distance (squared)
  double max_pair_residual_px = 0.6;  // a pair further than this from the fit is dropped
  // The fit holds when this share of the pairs agree, to max_residual_px RMS (a ray that ran
  // into a line or a shadow is one pair; a window where a quarter disagree is not a ball's edge).
  double min_pair_share = 0.75;
  double max_residual_px = 0.4;
  int iterations = 2;        // rays cast again from the centre found...
  double settled_px = 0.25;  // ...unless it moved less than this

  bool IsValid(std::string* error) const;
};

struct EdgeCentre {
  double cx = 0.0, cy = 0.0;  // the shape's centre (mid-exposure for a streak), px
  // Its widths across and along (a disc: both its diameter; a short streak: the ball's diameter
  // across the motion), from the opposite rays' edges, px; 0 where the fit says none (major of a
  // shape too long for the rays).
  double minor_diameter = 0.0, major_diameter = 0.0;
  int pairs = 0;             // opposite rays that agreed
  double residual_px = 0.0;  // RMS of their half-differences about the fit
  // The ball's colour (Y, U, V: the mean of the last rays' samples within half the minor
  // radius of where they started).
  double colour[3] = {0.0, 0.0, 0.0};
  // The side where the ball differs least from the background: each agreeing ray's colour
  // distance from its background between a third and two thirds of the way to its edge, fitted
  // as a + b cos(t) + c sin(t) over the rays' directions t; `faint` = -(b, c) / |(b, c)| (a unit
  // image direction; zero when fewer than 3 pairs agreed). A shaded half whose level nears the
  // floor's is where the half-level edge comes early (MeasureEdgeCentre's rule): the centre
  // found lies away from it and the width found is short by what that side lost.
  double faint[2] = {0.0, 0.0};
};

// The colour (Y, U, V) at (x, y), bilinear: luma at full resolution, chroma from its
// half-resolution samples. False outside the image.
bool ColourAt(const ImageView& image, double x, double y, double out[3]);

// The distance of two colours (Y, U, V) as the edge fit measures contrast: luma, and chroma
// weighted by chroma_weight (squared).
double ColourDistance(const double* a, const double* b, double chroma_weight);

// The centre of an edge fit moved back towards its faint side (EdgeCentre::faint) where its
// width is short of the ball's known width there (expected_px: from the point 2+ views place
// it at): by half of what was lost, less symmetric_px (the half-level contour of a blurred disc
// lies inside its edge on every side), at most max_share of expected_px (more is a hidden or
// merged view, not shade). The centre as it was without a faint side or an expected width.
struct ShadeOptions {
  double symmetric_px = 0.3;
  double max_share = 0.25;
  // FaintSideVote: a camera's faint side is agreed once this many of its views' edge fits found
  // one (0: never)...
  int camera_min_views = 10;
  // ...and their unit directions' mean has at least this length (1: all the same).
  double camera_agreement = 0.8;

  bool IsValid(std::string* error) const;
};
void UnshadeCentre(double width_px, const double faint[2], double expected_px,
                   const ShadeOptions& options, double* cx, double* cy);

// The faint side a camera's views agree on. The hall's light is fixed, so the edge fits of one
// camera's views that find a faint side mostly find the same one; a view whose own fit found
// none takes theirs (where its shaded half nears the background too closely for enough of its
// rays to agree, the fit fails: there the centre leans furthest to the lit side). Pure; one per
// camera.
class FaintSideVote {
 public:
  // A view's faint side (a unit image direction, EdgeCentre::faint); zero is no vote.
  void Add(const double faint[2]);
  // The agreed side (unit) into `out`; false while fewer than options.camera_min_views voted or
  // their mean is shorter than options.camera_agreement.
  bool Agreed(const ShadeOptions& options, double out[2]) const;

 private:
  double sum_[2] = {0.0, 0.0};
  int views_ = 0;
};

// `cx, cy`: a first guess of the centre (e.g. the colour region's centroid), within about half a
// radius; `radius_px`: the ball's radius guess (half the region's major axis for a streak).
// nullopt when too few opposite rays find an edge that agrees (too little contrast, the ball at
// the image border, a crowded window). Precondition: options valid.
std::optional<EdgeCentre> MeasureEdgeCentre(const ImageView& image, double cx, double cy,
                                            double radius_px,
                                            const EdgeCentreOptions& options = {});

// A disc merged on one side with a region of its colour (the ball against a hand or a shirt of
// its colour): the rays that end there find no edge, so opposite pairs seldom agree and
// MeasureEdgeCentre fails. Its centre and radius from single rays instead: each ray's edge
// r_i = R + o . u_i (o the centre's offset from the rays' origin, R the radius; first order in
// o) by least squares over the rays that find one within half a radius guess of it, dropping
// those further than max_ray_residual_px from the fit, the rays cast again from the new centre
// (edge.iterations, edge.settled_px). Holds when min_ray_share of the rays agree to
// edge.max_residual_px RMS and the agreeing rays' directions leave no gap wider than
// max_gap_deg: an arc of less than half the outline does not fix its centre. A disc only:
// minor = major = 2R; `pairs` counts the rays that agreed; no faint side. Preconditions as
// MeasureEdgeCentre's.
struct EdgeCircleOptions {
  // The rays (directions, step, reach, contrast, iterations, settled_px, max_residual_px; the
  // pairs' fields are not used).
  EdgeCentreOptions edge = [] {
    EdgeCentreOptions e;
    e.directions = 16;
    e.iterations = 3;
    return e;
  }();
  double min_ray_share = 0.5;
  double max_ray_residual_px = 0.6;
  double max_gap_deg = 180.0;

  bool IsValid(std::string* error) const;
};
std::optional<EdgeCentre> MeasureEdgeCircle(const ImageView& image, double cx, double cy,
                                            double radius_px,
                                            const EdgeCircleOptions& options = {});

}  // namespace p4::segment
