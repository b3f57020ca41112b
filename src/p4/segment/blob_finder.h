// Finding the ball in one image (paper §3.1 and §3.4): classify each pixel with the colour LUTs
// while run-length encoding each row, merge runs of neighbouring rows with a tree-based
// union-find with path compression, gather region statistics, sort regions by size.
//
// Works on the camera's own format (I420, NV12, YUYV; chroma at half resolution is looked up,
// never converted). Pixel stride s > 1 tests every s-th pixel of a row and fills the skipped
// pixels when both tested neighbours are in (paper §3.4). A region of interest limits the work.
//
// Pixel coordinates: centres at integers (OpenCV). Pure: no I/O; the finder keeps its buffers
// between calls, so a warmed-up finder does not allocate per frame.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/color_classes.h"

namespace p4::segment {

// A window [x0, x1) x [y0, y1) in pixels; empty means the whole image.
struct Roi {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool Contains(double x, double y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  // Centred window of the given size, clipped to the image (may become empty when outside).
  static Roi Around(double cx, double cy, int width, int height, int image_width, int image_height);
  Roi Clipped(int image_width, int image_height) const;
};

struct Run {
  int y = 0, x0 = 0, x1 = 0;  // [x0, x1) on row y
  int parent = 0;             // union-find parent (index into the runs)
};

struct Region {
  int area = 0;                        // pixels
  double cx = 0.0, cy = 0.0;           // centroid, pixels
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // bounding box [x0, x1) x [y0, y1)
  double diameter = 0.0;               // 2 sqrt(area / pi)
  double minor_diameter = 0.0;         // 4 sqrt(smallest eigenvalue of the pixel covariance): the
                                       // ball's diameter even when motion blur stretches the region
  double major_diameter = 0.0;
  bool touches_border = false;  // the region reaches the image edge (may be cut)
};

// Diameters of a region from its second moments (pixel variances cxx, cyy and covariance cxy):
// a uniform disc of diameter D has variance D^2 / 16 along every axis, so D = 4 sqrt(lambda).
struct MomentDiameters {
  double minor = 0.0, major = 0.0;
};
MomentDiameters DiametersFromMoments(double cxx, double cyy, double cxy);

// How much of the ellipse of a region's moments (diameters minor and major, px, each taken as at
// least a pixel) its area fills: 1 for a disc and for a ball blurred into a short streak; less
// for a ragged piece (a player's moving clothes). Not bounded above (a few pixels' region).
inline double Roundness(double area, double minor_diameter, double major_diameter) {
  return area / (0.25 * M_PI * std::max(1.0, minor_diameter) * std::max(1.0, major_diameter));
}

struct SegmentOptions {
  uint32_t mask = 0xffffffffu;  // classes that count as the object
  int stride = 1;               // test every stride-th pixel of a row (1-4)
  int min_area = 3;             // smaller regions are dropped (pixels)
  int max_regions = 16;         // keep the largest ones
  // I420 and NV12 at stride 1: classify each 2x2 block's chroma once, luma only where it can be
  // the object (same result; false: every pixel's three look-ups, the reference path).
  bool chroma_first = true;

  bool IsValid(std::string* error) const;
};

// Which 2x2 blocks may hold the object (e.g. those that differ from the background): one byte a
// block, row-major, `width` blocks a row; 0 = skip.
struct BlockMask {
  const uint8_t* data = nullptr;
  int width = 0, height = 0;
  bool Allows(int x, int y) const { return data[(y >> 1) * width + (x >> 1)] != 0; }
};

class BlobFinder {
 public:
  // Finds regions inside `roi` (the whole image when empty), largest first. Returns their
  // number. With `blocks`, only pixels of allowed blocks can be the object (I420 and NV12 at
  // stride 1). Preconditions: view planes valid for its format; options valid; the mask covers
  // the image.
  int Find(const ImageView& image, const ColorLut& lut, const Roi& roi,
           const SegmentOptions& options, std::vector<Region>* regions,
           const BlockMask* blocks = nullptr);

  // The runs of the last call (for overlays and tests).
  const std::vector<Run>& runs() const { return runs_; }

 private:
  std::vector<Run> runs_;
  std::vector<uint8_t> row_;  // classification of one row
  struct Candidate {
    int cx;
    uint32_t mask;
  };
  std::vector<Candidate> candidates_;  // chroma samples of the current chroma row that may be in
  struct Accum {
    int64_t area;
    double sx, sy, sxx, syy, sxy;
    int x0, y0, x1, y1;
  };
  std::vector<Accum> accum_;
};

}  // namespace p4::segment
