#include "p4/segment/blob_finder.h"

#include <algorithm>
#include <cmath>

#include "p4/segment/union_find.h"

namespace p4::segment {

Roi Roi::Around(double cx, double cy, int width, int height, int image_width, int image_height) {
  Roi roi;
  roi.x0 = static_cast<int>(std::floor(cx - width / 2.0));
  roi.y0 = static_cast<int>(std::floor(cy - height / 2.0));
  roi.x1 = roi.x0 + width;
  roi.y1 = roi.y0 + height;
  return roi.Clipped(image_width, image_height);
}

Roi Roi::Clipped(int image_width, int image_height) const {
  Roi r{std::max(0, x0), std::max(0, y0), std::min(image_width, x1), std::min(image_height, y1)};
  if (r.empty()) r = Roi{0, 0, 0, 0};
  return r;
}

MomentDiameters DiametersFromMoments(double cxx, double cyy, double cxy) {
  const double mean = 0.5 * (cxx + cyy);
  const double spread = std::sqrt(std::max(0.0, 0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy));
  return {4.0 * std::sqrt(std::max(0.0, mean - spread)),
          4.0 * std::sqrt(std::max(0.0, mean + spread))};
}

bool SegmentOptions::IsValid(std::string* error) const {
  if (stride < 1 || stride > 4) {
    if (error) *error = "stride must be in [1, 4]";
    return false;
  }
  if (min_area < 1 || max_regions < 1) {
    if (error) *error = "min_area and max_regions must be >= 1";
    return false;
  }
  if (mask == 0) {
    if (error) *error = "the class mask is empty";
    return false;
  }
  return true;
}

namespace {

// Per-format access to one row: Y of pixel x and the chroma pair of its 2x2 (or 2x1) block.
struct I420Row {
  const uint8_t *y, *u, *v;
  uint32_t Classify(const ColorLut& lut, int x) const {
    return lut.y[y[x]] & lut.u[u[x >> 1]] & lut.v[v[x >> 1]];
  }
};
struct Nv12Row {
  const uint8_t *y, *uv;
  uint32_t Classify(const ColorLut& lut, int x) const {
    const int c = (x >> 1) << 1;
    return lut.y[y[x]] & lut.u[uv[c]] & lut.v[uv[c + 1]];
  }
};
struct YuyvRow {
  const uint8_t* p;
  uint32_t Classify(const ColorLut& lut, int x) const {
    const int c = (x >> 1) << 2;
    return lut.y[p[2 * x]] & lut.u[p[c + 1]] & lut.v[p[c + 3]];
  }
};

template <typename Row>
void ClassifyRow(const Row& row, const ColorLut& lut, uint32_t mask, int x0, int x1, int stride,
                 uint8_t* out) {
  const int n = x1 - x0;
  if (stride == 1) {
    for (int i = 0; i < n; ++i) out[i] = (row.Classify(lut, x0 + i) & mask) != 0;
    return;
  }
  std::fill(out, out + n, uint8_t{0});
  int previous = -1;  // last tested index that was in
  for (int i = 0; i < n; i += stride) {
    const bool in = (row.Classify(lut, x0 + i) & mask) != 0;
    if (!in) {
      previous = -1;
      continue;
    }
    out[i] = 1;
    if (previous >= 0) std::fill(out + previous, out + i, uint8_t{1});  // both neighbours in
    previous = i;
  }
}

// Sum of x^2 for x in [0, m].
double SumSquares(double m) { return m < 0 ? 0.0 : m * (m + 1) * (2 * m + 1) / 6.0; }

}  // namespace

int BlobFinder::Find(const ImageView& image, const ColorLut& lut, const Roi& roi_in,
                     const SegmentOptions& options, std::vector<Region>* regions,
                     const BlockMask* blocks) {
  regions->clear();
  runs_.clear();
  const Roi roi = roi_in.empty() ? Roi{0, 0, image.width, image.height}
                                 : roi_in.Clipped(image.width, image.height);
  if (roi.empty()) return 0;
  const int n = roi.x1 - roi.x0;
  row_.resize(n);
  // Chroma first (I420, NV12, stride 1): a 2x2 block's chroma is shared, so U and V are looked up
  // once per block and luma only where the chroma can be the ball — the ball is small and most
  // blocks are out at once. Same runs as the per-pixel path (tested).
  const bool chroma_first =
      options.chroma_first && options.stride == 1 &&
      (image.format == PixelFormat::kI420 || image.format == PixelFormat::kNV12);
  const int cx0 = roi.x0 >> 1, cx1 = (roi.x1 + 1) >> 1;
  int chroma_row = -1;
  std::size_t previous_row_begin = 0, previous_row_end = 0;
  for (int y = roi.y0; y < roi.y1; ++y) {
    const std::size_t row_begin = runs_.size();
    if (chroma_first) {
      if ((y >> 1) != chroma_row) {
        chroma_row = y >> 1;
        candidates_.clear();
        if (image.format == PixelFormat::kI420) {
          const uint8_t* u = image.planes[1].Row(chroma_row);
          const uint8_t* v = image.planes[2].Row(chroma_row);
          for (int cx = cx0; cx < cx1; ++cx) {
            const uint32_t m = lut.u[u[cx]] & lut.v[v[cx]] & options.mask;
            if (m && (!blocks || blocks->data[chroma_row * blocks->width + cx])) {
              candidates_.push_back({cx, m});
            }
          }
        } else {
          const uint8_t* uv = image.planes[1].Row(chroma_row);
          for (int cx = cx0; cx < cx1; ++cx) {
            const uint32_t m = lut.u[uv[2 * cx]] & lut.v[uv[2 * cx + 1]] & options.mask;
            if (m && (!blocks || blocks->data[chroma_row * blocks->width + cx])) {
              candidates_.push_back({cx, m});
            }
          }
        }
      }
      const uint8_t* luma = image.planes[0].Row(y);
      int open = -1, end = -1;  // the run being built: [open, end)
      for (const auto& [cx, m] : candidates_) {
        for (int x = std::max(2 * cx, roi.x0); x < std::min(2 * cx + 2, roi.x1); ++x) {
          if (!(lut.y[luma[x]] & m)) continue;
          if (open >= 0 && x == end) {
            ++end;
            continue;
          }
          if (open >= 0) {
            const int index = static_cast<int>(runs_.size());
            runs_.push_back({y, open, end, index});
          }
          open = x, end = x + 1;
        }
      }
      if (open >= 0) {
        const int index = static_cast<int>(runs_.size());
        runs_.push_back({y, open, end, index});
      }
    } else {
      switch (image.format) {
        case PixelFormat::kI420:
          ClassifyRow(I420Row{image.planes[0].Row(y), image.planes[1].Row(y >> 1),
                              image.planes[2].Row(y >> 1)},
                      lut, options.mask, roi.x0, roi.x1, options.stride, row_.data());
          break;
        case PixelFormat::kNV12:
          ClassifyRow(Nv12Row{image.planes[0].Row(y), image.planes[1].Row(y >> 1)}, lut,
                      options.mask, roi.x0, roi.x1, options.stride, row_.data());
          break;
        case PixelFormat::kYUYV:
          ClassifyRow(YuyvRow{image.planes[0].Row(y)}, lut, options.mask, roi.x0, roi.x1,
                      options.stride, row_.data());
          break;
      }
      // Run-length encode the row.
      for (int i = 0; i < n;) {
        if (!row_[i]) {
          ++i;
          continue;
        }
        int j = i + 1;
        while (j < n && row_[j]) ++j;
        const int index = static_cast<int>(runs_.size());
        runs_.push_back({y, roi.x0 + i, roi.x0 + j, index});
        i = j;
      }
    }
    internal::JoinWithRowAbove(runs_, previous_row_begin, previous_row_end, row_begin);
    previous_row_begin = row_begin;
    previous_row_end = runs_.size();
  }

  // Region statistics, accumulated on each run's root.
  accum_.assign(runs_.size(), Accum{0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const Run& run = runs_[i];
    Accum& a = accum_[static_cast<std::size_t>(internal::FindRoot(runs_, static_cast<int>(i)))];
    const double len = run.x1 - run.x0;
    const double sx = len * (run.x0 + run.x1 - 1) / 2.0;
    const double sxx = SumSquares(run.x1 - 1.0) - SumSquares(run.x0 - 1.0);
    if (a.area == 0) {
      a.x0 = run.x0, a.x1 = run.x1, a.y0 = run.y, a.y1 = run.y + 1;
    } else {
      a.x0 = std::min(a.x0, run.x0), a.x1 = std::max(a.x1, run.x1);
      a.y0 = std::min(a.y0, run.y), a.y1 = std::max(a.y1, run.y + 1);
    }
    a.area += run.x1 - run.x0;
    a.sx += sx;
    a.sy += len * run.y;
    a.sxx += sxx;
    a.syy += len * run.y * run.y;
    a.sxy += sx * run.y;
  }
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const Accum& a = accum_[i];
    if (runs_[i].parent != static_cast<int>(i) || a.area < options.min_area) continue;
    Region region;
    region.area = static_cast<int>(a.area);
    const double area = static_cast<double>(a.area);
    region.cx = a.sx / area;
    region.cy = a.sy / area;
    region.x0 = a.x0, region.x1 = a.x1, region.y0 = a.y0, region.y1 = a.y1;
    region.diameter = 2.0 * std::sqrt(area / M_PI);
    // Covariance of the pixel squares (each pixel adds 1/12 of its own extent).
    const double cxx = a.sxx / area - region.cx * region.cx + 1.0 / 12.0;
    const double cyy = a.syy / area - region.cy * region.cy + 1.0 / 12.0;
    const double cxy = a.sxy / area - region.cx * region.cy;
    const MomentDiameters d = DiametersFromMoments(cxx, cyy, cxy);
    region.minor_diameter = d.minor;
    region.major_diameter = d.major;
    region.touches_border = a.x0 == 0 || a.y0 == 0 || a.x1 == image.width || a.y1 == image.height;
    regions->push_back(region);
  }
  std::sort(regions->begin(), regions->end(),
            [](const Region& a, const Region& b) { return a.area > b.area; });
  if (static_cast<int>(regions->size()) > options.max_regions) {
    regions->resize(options.max_regions);
  }
  return static_cast<int>(regions->size());
}

}  // namespace p4::segment
