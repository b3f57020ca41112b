#include "p4/segment/ball_outline.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "p4/segment/ball_edge.h"

namespace p4::segment {
namespace {

struct Circle {
  bool inside_image = false;
  double contrast = 0.0;  // mean over the normals (those off the ball's hue count 0)
  double share = 0.0;     // of the normals reaching min_contrast
};

class OutlineScorer {
 public:
  OutlineScorer(const ImageView& image, double radius_px, const double ball[3],
                const OutlineOptions& options)
      : image_(image), radius_(radius_px), options_(options) {
    const double hue = std::atan2(ball[2] - 128.0, ball[1] - 128.0);
    hue_u_ = std::cos(hue);
    hue_v_ = std::sin(hue);
    cos_hue_limit_ = std::cos(options.max_hue_deg * std::numbers::pi / 180.0);
    for (int k = 0; k < options.directions; ++k) {
      const double a = 2.0 * std::numbers::pi * k / options.directions;
      normals_.push_back({std::cos(a), std::sin(a)});
    }
  }

  Circle Score(double cx, double cy) const { return Score(cx, cy, radius_); }

  // Every stride-th normal only: a coarse look.
  Circle Score(double cx, double cy, double radius, int stride = 1) const {
    Circle out;
    const double r_out = radius + options_.across_px;
    const double r_in = std::max(0.0, radius - options_.across_px);
    double sum = 0.0;
    int on = 0;
    int counted = 0;
    for (std::size_t k = 0; k < normals_.size(); k += stride) {
      const auto& [ux, uy] = normals_[k];
      ++counted;
      double a[3], b[3];
      if (!ColourAt(image_, cx + r_out * ux, cy + r_out * uy, a) ||
          !ColourAt(image_, cx + r_in * ux, cy + r_in * uy, b)) {
        return out;
      }
      // The inside sample's hue against the ball's: the cosine of the angle between them.
      const double du = b[1] - 128.0, dv = b[2] - 128.0;
      const double chroma = std::hypot(du, dv);
      if (!(chroma > 0.0) || (du * hue_u_ + dv * hue_v_) / chroma < cos_hue_limit_) continue;
      const double g = ColourDistance(a, b, options_.chroma_weight);
      sum += g;
      if (g >= options_.min_contrast) ++on;
    }
    const double n = static_cast<double>(counted);
    out.inside_image = true;
    out.contrast = sum / n;
    out.share = on / n;
    return out;
  }

 private:
  const ImageView& image_;
  double radius_;
  const OutlineOptions& options_;
  double hue_u_ = 0.0, hue_v_ = 0.0;  // the ball's hue: a unit direction in (U, V) about grey
  double cos_hue_limit_ = 0.0;
  std::vector<std::pair<double, double>> normals_;
};

// The peak's offset from the middle of three samples a step apart, within half a step.
double ParabolaPeak(double left, double mid, double right) {
  const double curvature = left - 2.0 * mid + right;
  if (!(curvature < 0.0)) return 0.0;
  return std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
}

}  // namespace

bool OutlineOptions::IsValid(std::string* error) const {
  if (directions < 8 || !(across_px > 0.0) || !(coarse_px > 0.0) ||
      !(fine_px > 0.0 && fine_px <= coarse_px) || !(chroma_weight >= 0.0) ||
      !(max_hue_deg > 0.0 && max_hue_deg <= 180.0) || !(min_chroma >= 0.0) ||
      !(min_contrast > 0.0) || !(min_share >= 0.0 && min_share <= 1.0) ||
      !(max_radius_ratio >= 1.0)) {
    if (error) {
      *error =
          "outline: directions must be at least 8, across_px, coarse_px and min_contrast "
          "positive, fine_px in (0, coarse_px], chroma_weight and min_chroma at "
          "least 0, max_hue_deg in (0, 180], min_share in [0, 1] and max_radius_ratio at least 1";
    }
    return false;
  }
  return true;
}

std::optional<OutlineCentre> FitOutline(const ImageView& image, double cx, double cy,
                                        double radius_px, double max_shift_px, const double ball[3],
                                        const OutlineOptions& options) {
  if (!(radius_px > 0.0) || !(max_shift_px >= 0.0) ||
      std::hypot(ball[1] - 128.0, ball[2] - 128.0) < options.min_chroma) {
    return std::nullopt;
  }
  const OutlineScorer scorer(image, radius_px, ball, options);
  // Coarse: a square grid about the guess; a best point on its border is something stronger
  // beyond the search, not this ball.
  const int half = static_cast<int>(std::ceil(max_shift_px / options.coarse_px));
  double best = -1.0, bx = cx, by = cy;
  bool border = false;
  for (int j = -half; j <= half; ++j) {
    for (int i = -half; i <= half; ++i) {
      const double x = cx + i * options.coarse_px, y = cy + j * options.coarse_px;
      const Circle c = scorer.Score(x, y, radius_px, 2);
      if (c.inside_image && c.contrast > best) {
        best = c.contrast;
        bx = x;
        by = y;
        border = std::abs(i) == half || std::abs(j) == half;
      }
    }
  }
  if (best <= 0.0 || border) return std::nullopt;
  // Fine: about the coarse best, within a coarse step.
  const int fine_half = static_cast<int>(std::round(options.coarse_px / options.fine_px));
  const double x0 = bx, y0 = by;
  best = -1.0;  // all the normals from here on
  for (int j = -fine_half; j <= fine_half; ++j) {
    for (int i = -fine_half; i <= fine_half; ++i) {
      const double x = x0 + i * options.fine_px, y = y0 + j * options.fine_px;
      const Circle c = scorer.Score(x, y);
      if (c.inside_image && c.contrast > best) {
        best = c.contrast;
        bx = x;
        by = y;
      }
    }
  }
  // Sub-step: a parabola through the best and its neighbours on each axis.
  const double step = options.fine_px;
  const auto at = [&](double x, double y) {
    const Circle c = scorer.Score(x, y);
    return c.inside_image ? c.contrast : 0.0;
  };
  const double px = ParabolaPeak(at(bx - step, by), best, at(bx + step, by));
  const double py = ParabolaPeak(at(bx, by - step), best, at(bx, by + step));
  OutlineCentre out;
  out.cx = bx + px * step;
  out.cy = by + py * step;
  // The radius: where the contrast across the circle about that centre peaks, within
  // max_radius_ratio of the one given.
  const int radii =
      static_cast<int>(std::ceil((options.max_radius_ratio - 1.0) * radius_px / options.fine_px));
  double best_r = radius_px, best_rc = -1.0;
  std::vector<double> contrast(2 * radii + 1, 0.0);
  for (int i = -radii; i <= radii; ++i) {
    const Circle c = scorer.Score(out.cx, out.cy, radius_px + i * options.fine_px);
    contrast[i + radii] = c.inside_image ? c.contrast : 0.0;
    if (contrast[i + radii] > best_rc) {
      best_rc = contrast[i + radii];
      best_r = radius_px + i * options.fine_px;
    }
  }
  const int ib = static_cast<int>(std::lround((best_r - radius_px) / options.fine_px)) + radii;
  // A peak at the range's end is a thing of another size (a speck, a larger blob).
  if (ib <= 0 || ib >= 2 * radii) return std::nullopt;
  best_r += options.fine_px * ParabolaPeak(contrast[ib - 1], contrast[ib], contrast[ib + 1]);
  out.radius = best_r;
  if (std::hypot(out.cx - cx, out.cy - cy) > max_shift_px) return std::nullopt;
  const Circle c = scorer.Score(out.cx, out.cy);
  if (!c.inside_image || c.share < options.min_share) return std::nullopt;
  out.contrast = c.contrast;
  out.share = c.share;
  return out;
}

}  // namespace p4::segment
