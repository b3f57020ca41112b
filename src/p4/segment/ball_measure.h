// A finer measure of a found region (beyond the paper): the binary region's size depends on the
// colour boxes and on the background (chroma at half resolution bleeds into the floor), which
// makes the depth from the ball's diameter (paper §3.2) error-prone. Here each pixel of a window
// around the region gets a coverage alpha from its luma between the local background (the
// window's border, less its own noise) and the ball's own level; the alpha-weighted moments give
// the area, the centroid and the blur-proof minor diameter to a fraction of a pixel.
#pragma once

#include <optional>

#include "p4/core/image.h"
#include "p4/segment/blob_finder.h"

namespace p4::segment {

struct BallMeasure {
  double cx = 0.0, cy = 0.0;    // alpha-weighted centroid, pixels
  double diameter = 0.0;        // 2 sqrt(sum alpha / pi)
  double minor_diameter = 0.0;  // 4 sqrt(smallest eigenvalue of the weighted covariance)
  double contrast = 0.0;        // ball luma minus background luma (8-bit levels)
};

struct BallMeasureOptions {
  int margin_px = 3;           // window = region box grown by this (and by a quarter of its size)
  int fringe_px = 2;           // coverage is summed over the region's box grown by this
  double min_contrast = 18.0;  // below it the luma says too little: no measure
};

// nullopt when the region touches the image border or the contrast is too low.
std::optional<BallMeasure> MeasureBall(const ImageView& image, const Region& region,
                                       const BallMeasureOptions& options = {});

}  // namespace p4::segment
