// The centre of a ball of known size from its outline (beyond the paper, whose centre is the
// colour region's centroid, §3.1). Where two or more views place the ball, its diameter in each
// image is known to a few per cent; where the ball's shading crosses the background's level
// (lamps above a floor of the ball's own hue: a lit cap brighter than the floor, a shaded bottom
// darker, and between them a band of the floor's colour), the colour tables take the lit cap and
// the edge rays (ball_edge.h), which start inside the ball, lose their contrast in that band: the
// centre found is the cap's, up to a third of the ball toward the lamps.
//
// The outline of a disc of the known radius is what such a ball still shows whole: the lit arc
// against the floor above, the shaded arc against it below. The centre is where the colour's
// contrast across that circle (the colour `across_px` outside it against `across_px` inside,
// along each of `directions` normals) is greatest on average, searched on a grid about the guess
// and refined to a parabola's peak. A normal counts only where its inside sample has the ball's
// hue (the angle of (U, V) about grey: shading scales luma and chroma alike, so the shaded half
// keeps it): a table's edge or a line beside the ball is a stronger edge than the ball's, but
// the colour inside it is not the ball's.
//
// Pixel coordinates: centres at integers. Pure.
#pragma once

#include <optional>
#include <string>

#include "p4/core/image.h"

namespace p4::segment {

struct OutlineOptions {
  int directions = 32;          // normals around the circle
  double across_px = 1.0;       // the contrast from this far inside the circle to as far outside
  double coarse_px = 1.0;       // the centre searched on a grid this fine, then about its best...
  double fine_px = 0.25;        // ...on this one, within coarse_px
  double chroma_weight = 0.25;  // of U and V against Y in the contrast (squared), as ball_edge.h
  double max_hue_deg = 35.0;    // a normal's inside sample within this of the ball's hue counts
  // A ball whose colour is greyer than this (|(U, V) - 128|, 8-bit levels) has no hue to hold
  // the inside to: no fit.
  double min_chroma = 12.0;
  double min_contrast = 12.0;  // a normal is on the ball's outline where its contrast reaches this
  double min_share = 0.25;     // the fit holds when this share of the normals are
  // The radius measured about the centre found: the circle's contrast's peak within this ratio
  // of the one given, either way (a peak at either end: no fit).
  double max_radius_ratio = 1.3;

  bool IsValid(std::string* error) const;
};

struct OutlineCentre {
  double cx = 0.0, cy = 0.0;  // the disc's centre, px
  double radius = 0.0;        // its radius measured about that centre, px
  double contrast = 0.0;      // the mean contrast across its circle (hue-held normals), levels
  double share = 0.0;         // of the normals reaching min_contrast
};

// `cx, cy`: a guess of the centre (e.g. a lit cap's centre); `radius_px`: the ball's radius there
// (from the point other views place it at); `max_shift_px`: how far the centre may lie from the
// guess (a cap w px high lies inside the ball: its centre is within radius - w / 2 of the ball's,
// plus a margin for the blur); `ball`: the ball's colour (Y, U, V; e.g. the cap's). nullopt when
// the ball is grey, the best centre lies on the search's border or beyond max_shift_px
// (something beyond it is stronger: a banner's lettering of the ball's colour, a table's edge),
// the contrast peaks at an end of the radii searched (a speck, a larger blob), too few normals
// reach min_contrast, or the circle leaves the image (and for max_shift_px under a coarse step:
// nothing to search). Precondition: options valid.
std::optional<OutlineCentre> FitOutline(const ImageView& image, double cx, double cy,
                                        double radius_px, double max_shift_px, const double ball[3],
                                        const OutlineOptions& options = {});

}  // namespace p4::segment
