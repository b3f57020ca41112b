#include "p4/segment/ball_measure.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "p4/core/robust.h"

namespace p4::segment {
namespace {

inline uint8_t Luma(const ImageView& image, int x, int y) {
  const uint8_t* row = image.planes[0].Row(y);
  return image.format == PixelFormat::kYUYV ? row[2 * x] : row[x];
}

}  // namespace

std::optional<BallMeasure> MeasureBall(const ImageView& image, const Region& region,
                                       const BallMeasureOptions& options) {
  if (region.touches_border) return std::nullopt;
  const int grow = options.margin_px + (region.x1 - region.x0 + region.y1 - region.y0) / 8;
  const int x0 = region.x0 - grow, y0 = region.y0 - grow, x1 = region.x1 + grow,
            y1 = region.y1 + grow;
  if (x0 < 0 || y0 < 0 || x1 > image.width || y1 > image.height) return std::nullopt;
  // Background: median luma of the window's border ring.
  std::vector<uint8_t> ring;
  for (int x = x0; x < x1; ++x)
    ring.push_back(Luma(image, x, y0)), ring.push_back(Luma(image, x, y1 - 1));
  for (int y = y0 + 1; y < y1 - 1; ++y)
    ring.push_back(Luma(image, x0, y)), ring.push_back(Luma(image, x1 - 1, y));
  const double background = MedianInPlace(ring);
  // The background's own spread (sensor noise, texture), robustly: 1.4826 x median |deviation|.
  std::vector<double> deviation(ring.begin(), ring.end());
  const double floor = std::max(2.0, 2.5 * RobustSigmaInPlace(deviation, background));
  // Ball level: the 75th percentile of the luma difference inside the region's box, taken on the
  // side (brighter or darker) where the region's centre lies.
  const int cx = static_cast<int>(std::lround(region.cx)),
            cy = static_cast<int>(std::lround(region.cy));
  const double sign = Luma(image, cx, cy) >= background ? 1.0 : -1.0;
  std::vector<double> inside;
  for (int y = region.y0; y < region.y1; ++y) {
    for (int x = region.x0; x < region.x1; ++x)
      inside.push_back(sign * (Luma(image, x, y) - background));
  }
  std::nth_element(inside.begin(), inside.begin() + inside.size() * 3 / 4, inside.end());
  const double contrast = inside[inside.size() * 3 / 4];
  if (contrast < options.min_contrast || contrast < 2.0 * floor) return std::nullopt;
  // Coverage is summed near the region only (its box and the blur's fringe), so that a bright
  // neighbour inside the window (a table edge line, a lamp) is not counted as ball.
  const int f = options.fringe_px;
  const int ax0 = std::max(x0, region.x0 - f), ay0 = std::max(y0, region.y0 - f),
            ax1 = std::min(x1, region.x1 + f), ay1 = std::min(y1, region.y1 + f);
  double sw = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int y = ay0; y < ay1; ++y) {
    for (int x = ax0; x < ax1; ++x) {
      // Differences within the background's noise count as background.
      const double a = std::clamp(
          (sign * (Luma(image, x, y) - background) - floor) / (contrast - floor), 0.0, 1.0);
      if (a <= 0.0) continue;
      sw += a, sx += a * x, sy += a * y, sxx += a * x * x, syy += a * y * y, sxy += a * x * y;
    }
  }
  if (sw < 1.0) return std::nullopt;
  BallMeasure m;
  m.contrast = sign * contrast;
  m.cx = sx / sw;
  m.cy = sy / sw;
  m.diameter = 2.0 * std::sqrt(sw / M_PI);
  const double cxx = sxx / sw - m.cx * m.cx + 1.0 / 12.0;
  const double cyy = syy / sw - m.cy * m.cy + 1.0 / 12.0;
  const double cxy = sxy / sw - m.cx * m.cy;
  m.minor_diameter = DiametersFromMoments(cxx, cyy, cxy).minor;
  return m;
}

}  // namespace p4::segment
