#include "p4/segment/colour_learning.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "p4/segment/pixel_access.h"

namespace p4::segment {

ColorClassSet AnyColour() {
  ColorClassSet set;
  set.classes.push_back({"ball_any", {0, 255}, {0, 255}, {0, 255}});
  return set;
}

bool ColourLearningOptions::IsValid(std::string* error) const {
  if (!(core_share > 0.0 && core_share <= 1.0) || !(min_sigmas >= 0.0) || min_samples < 1 ||
      boxes < 1 || boxes > 8 || margin < 0 || margin > 64) {
    if (error)
      *error = "colour learning: core share in (0, 1], samples >= 1, 1-8 boxes, margin 0-64";
    return false;
  }
  return true;
}

void ColourSamples::AddDisc(const ImageView& image, const Eigen::Vector2d& centre,
                            double diameter_px, const ColourLearningOptions& options,
                            const BackgroundModel* background) {
  const double r = 0.5 * diameter_px * options.core_share;
  if (!(r > 0.0)) return;
  const bool compare = background && background->ready() &&
                       background->width() == (image.width & ~1) &&
                       background->height() == (image.height & ~1);
  const double k2 = options.min_sigmas * options.min_sigmas;
  const int x0 = std::max(0, static_cast<int>(std::floor(centre.x() - r)));
  const int x1 = std::min(image.width - 1, static_cast<int>(std::ceil(centre.x() + r)));
  const int y0 = std::max(0, static_cast<int>(std::floor(centre.y() - r)));
  const int y1 = std::min(image.height - 1, static_cast<int>(std::ceil(centre.y() + r)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if ((x - centre.x()) * (x - centre.x()) + (y - centre.y()) * (y - centre.y()) > r * r) {
        continue;
      }
      if (compare && (x >= background->width() || y >= background->height() ||
                      background->BlockDistance2(image, x / 2, y / 2) <= k2)) {
        continue;
      }
      YuvSample s{internal::LumaAt(image, x, y), 0, 0};
      internal::ChromaAt(image, x, y, &s.u, &s.v);
      samples_.push_back(s);
    }
  }
}

bool ColourSamples::Learn(const ColourLearningOptions& options, LearnedColour* out,
                          std::string* error) const {
  if (size() < options.min_samples) {
    if (error) {
      *error = fmt::format("{} pixels of the ball were seen, {} are needed", size(),
                           options.min_samples);
    }
    return false;
  }
  // The lit colour: the median of the brightest band.
  std::vector<YuvSample> sorted = samples_;
  std::sort(sorted.begin(), sorted.end(),
            [](const YuvSample& a, const YuvSample& b) { return a.y < b.y; });
  const std::size_t lo = sorted.size() * (options.boxes - 1) / options.boxes;
  std::vector<float> ys, us, vs;
  for (std::size_t i = lo; i < sorted.size(); ++i) {
    ys.push_back(sorted[i].y), us.push_back(sorted[i].u), vs.push_back(sorted[i].v);
  }
  const auto median = [](std::vector<float> x) {
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return x[x.size() / 2];
  };
  const Yuv lit{median(ys), median(us), median(vs)};
  out->ball.lit = lit;
  // Shading scales the ball's colour along the line from black to it (ball_colour.h): a sample's
  // shade is its luma's share of the lit luma, and its chroma off that line at its shade is not
  // the ball (the hall at the disc's edge, a hand). Samples farther off than 3 robust sigmas (at
  // least 4 levels) are left out.
  const Yuv& k = kBlack;
  const auto on_line = [&](double shade, double lit_c, double black_c) {
    return black_c + shade * (lit_c - black_c);
  };
  std::vector<double> shade(samples_.size());
  std::vector<float> off(samples_.size());
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    const YuvSample& p = samples_[i];
    shade[i] = std::max(0.0, (p.y - double{k.y}) / std::max(1.0, double{lit.y} - k.y));
    off[i] = static_cast<float>(
        std::hypot(p.u - on_line(shade[i], lit.u, k.u), p.v - on_line(shade[i], lit.v, k.v)));
  }
  const float med = median(off);
  std::vector<float> dev(off.size());
  for (std::size_t i = 0; i < off.size(); ++i) dev[i] = std::abs(off[i] - med);
  // (At most max_off_line: a spread wider than that is a mixture, the ball and something else.)
  const double bound = std::clamp(med + 3.0 * 1.4826 * median(dev), 4.0, options.max_off_line);
  // The classes follow that line: `boxes` bands of shade between the inliers' 2nd and 98th
  // percentiles (not darker than a quarter of the lit colour: near black every colour meets the
  // line), each box the line's colour over its band, widened by the bound and the margin.
  std::vector<float> shades;
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    if (off[i] <= bound && shade[i] >= 0.25) shades.push_back(static_cast<float>(shade[i]));
  }
  if (static_cast<int>(shades.size()) < options.min_samples / 2) {
    if (error) *error = "the ball's pixels do not share one colour";
    return false;
  }
  std::sort(shades.begin(), shades.end());
  const double s0 = shades[shades.size() * 2 / 100];
  const double s1 = shades[std::min(shades.size() - 1, shades.size() * 98 / 100)];
  const auto level = [](double x) {
    return static_cast<uint8_t>(std::clamp(std::lround(x), 0L, 255L));
  };
  const double tolerance = bound + options.margin;
  out->classes.classes.clear();
  for (int b = 0; b < options.boxes; ++b) {
    const double a = s0 + (s1 - s0) * b / options.boxes;
    const double z = s0 + (s1 - s0) * (b + 1) / options.boxes;
    ColorClass box;
    box.name = fmt::format("ball_{}", b);
    box.y = {level(on_line(a, lit.y, k.y) - options.margin),
             level(on_line(z, lit.y, k.y) + options.margin)};
    const auto range = [&](double lit_c, double black_c) {
      const double ca = on_line(a, lit_c, black_c), cz = on_line(z, lit_c, black_c);
      return std::array<uint8_t, 2>{level(std::min(ca, cz) - tolerance),
                                    level(std::max(ca, cz) + tolerance)};
    };
    box.u = range(lit.u, k.u);
    box.v = range(lit.v, k.v);
    out->classes.classes.push_back(box);
  }
  out->samples = static_cast<int>(shades.size());
  return true;
}

}  // namespace p4::segment
