#include "p4/segment/streak_search.h"

#include <algorithm>
#include <cmath>

#include "p4/core/robust.h"
#include "p4/segment/pixel_access.h"

namespace p4::segment {

bool StreakSearchOptions::IsValid(std::string* error) const {
  const bool shares_ok =
      !length_shares.empty() && std::all_of(length_shares.begin(), length_shares.end(),
                                            [](double s) { return s > 0.0 && s <= 1.0; });
  if (!(search_px > 0.0) || !(coarse_step_px > 0.0) || !shares_ok || angles < 1 ||
      !(angle_step_px > 0.0) || !(min_snr > 0.0) || null_samples < 8 || !(null_reach_px > 0.0) ||
      !(min_share_ratio > 0.0 && max_share_ratio > min_share_ratio) || !(max_ring_ratio > 0.0) ||
      !(shade > 0.0) || !(min_contrast >= 0.0) || !(chroma_weight >= 0.0)) {
    if (error) {
      *error =
          "streak search: positive search, steps, angles, SNR, reach and shading; length shares "
          "in (0, 1]; at least 8 null samples; min share ratio < max share ratio";
    }
    return false;
  }
  return true;
}

StreakSearch::Sums StreakSearch::Template(double cx, double cy, double ux, double uy, double length,
                                          double inner, double outer, double clip) const {
  // A rotated grid of unit spacing over the capsule around the segment; m and e bilinear.
  Sums s;
  const double half = 0.5 * length;
  const int na = static_cast<int>(std::ceil(half + outer)), nc = static_cast<int>(std::ceil(outer));
  for (int i = -na; i <= na; ++i) {
    const double along = std::clamp(static_cast<double>(i), -half, half);
    for (int j = -nc; j <= nc; ++j) {
      const double da = i - along;
      const double dist = std::hypot(da, static_cast<double>(j));
      if (dist > outer || (inner >= 0.0 && dist <= inner)) continue;
      const double x = cx + i * ux - j * uy - x0_, y = cy + i * uy + j * ux - y0_;
      const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
      if (xi < 0 || yi < 0 || xi + 1 >= w_ || yi + 1 >= h_) continue;
      const double fx = x - xi, fy = y - yi;
      const std::size_t k = static_cast<std::size_t>(yi) * w_ + xi;
      const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy,
                   w11 = fx * fy;
      const double m = w00 * m_[k] + w10 * m_[k + 1] + w01 * m_[k + w_] + w11 * m_[k + w_ + 1];
      const double e = w00 * e_[k] + w10 * e_[k + 1] + w01 * e_[k + w_] + w11 * e_[k + w_ + 1];
      s.m += std::clamp(m, -clip * e, clip * e);
      s.e += e;
      ++s.n;
    }
  }
  return s;
}

void StreakSearch::BuildShape(double ux, double uy, double length, double radius) {
  // Pixels whose centres lie within `radius` of the segment through the origin.
  shape_.clear();
  const double half = 0.5 * length;
  const int reach = static_cast<int>(std::ceil(half + radius));
  shape_x0_ = shape_y0_ = reach, shape_x1_ = shape_y1_ = -reach;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const double along = std::clamp(dx * ux + dy * uy, -half, half);
      if (std::hypot(dx - along * ux, dy - along * uy) > radius) continue;
      shape_.push_back(dy * w_ + dx);
      shape_x0_ = std::min(shape_x0_, dx), shape_x1_ = std::max(shape_x1_, dx);
      shape_y0_ = std::min(shape_y0_, dy), shape_y1_ = std::max(shape_y1_, dy);
    }
  }
}

StreakSearch::Sums StreakSearch::ShapeSums(int cx, int cy, double clip) const {
  Sums s;
  const int x = cx - x0_, y = cy - y0_;
  if (x + shape_x0_ < 0 || y + shape_y0_ < 0 || x + shape_x1_ >= w_ || y + shape_y1_ >= h_) {
    return s;  // reaches outside the window: not considered
  }
  const std::ptrdiff_t base = static_cast<std::ptrdiff_t>(y) * w_ + x;
  const auto c = static_cast<float>(clip);
  float m = 0.0f, e = 0.0f;
  for (const int offset : shape_) {
    const float ek = e_[static_cast<std::size_t>(base + offset)];
    m += std::clamp(m_[static_cast<std::size_t>(base + offset)], -c * ek, c * ek);
    e += ek;
  }
  s.m = m, s.e = e, s.n = static_cast<int>(shape_.size());
  return s;
}

double StreakSearch::ColourResidual(const ImageView& image, const BackgroundModel& bg,
                                    const BallColour& ball, const StreakHit& hit,
                                    double diameter_px, const StreakSearchOptions& o) const {
  // Every pixel within r + margin of the segment: sums of what is seen and of the background.
  const double reach = 0.5 * diameter_px + 2.0;
  const double ux = std::cos(hit.angle), uy = std::sin(hit.angle), half = 0.5 * hit.length_px;
  const int x0 = std::max(0, static_cast<int>(std::floor(hit.cx - half - reach)));
  const int x1 = std::min(bg.width() - 1, static_cast<int>(std::ceil(hit.cx + half + reach)));
  const int y0 = std::max(0, static_cast<int>(std::floor(hit.cy - half - reach)));
  const int y1 = std::min(bg.height() - 1, static_cast<int>(std::ceil(hit.cy + half + reach)));
  double so[3] = {0, 0, 0}, sb[3] = {0, 0, 0};
  int n = 0;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double dx = x - hit.cx, dy = y - hit.cy;
      const double along = std::clamp(dx * ux + dy * uy, -half, half);
      if (std::hypot(dx - along * ux, dy - along * uy) > reach) continue;
      uint8_t u = 128, v = 128;
      internal::ChromaAt(image, x, y, &u, &v);
      const Yuv block = bg.Block(x / 2, y / 2);
      so[0] += internal::LumaAt(image, x, y), so[1] += u, so[2] += v;
      sb[0] += bg.Luma(x, y), sb[1] += block.u, sb[2] += block.v;
      ++n;
    }
  }
  if (n == 0) return 1.0;
  const Yuv seen{static_cast<float>(so[0] / n), static_cast<float>(so[1] / n),
                 static_cast<float>(so[2] / n)};
  const Yuv back{static_cast<float>(sb[0] / n), static_cast<float>(sb[1] / n),
                 static_cast<float>(sb[2] / n)};
  UnmixOptions unmix;
  unmix.chroma_weight = o.chroma_weight;
  const Unmixed u = Unmix(seen, back, ball, unmix);
  return u.difference > 1e-6 && u.alpha > 0.0 ? u.residual / u.difference : 1.0;
}

std::optional<StreakHit> StreakSearch::Find(const ImageView& image, const BackgroundModel& bg,
                                            const BallColour& ball, double mid_x, double mid_y,
                                            double dir_x, double dir_y, double max_length_px,
                                            double diameter_px, const StreakSearchOptions& o) {
  if (!bg.ready() || !(diameter_px > 0.0) || !(max_length_px >= 0.0)) return std::nullopt;
  const double r = 0.5 * diameter_px;
  // The window: the search, the null's reach and the longest template around it.
  const double reach = std::max(o.search_px, o.null_reach_px) + 0.5 * max_length_px + r + 3.0;
  x0_ = std::max(0, static_cast<int>(std::floor(mid_x - reach)));
  y0_ = std::max(0, static_cast<int>(std::floor(mid_y - reach)));
  const int x1 = std::min(bg.width(), static_cast<int>(std::ceil(mid_x + reach)) + 1);
  const int y1 = std::min(bg.height(), static_cast<int>(std::ceil(mid_y + reach)) + 1);
  w_ = x1 - x0_, h_ = y1 - y0_;
  if (w_ < 4 || h_ < 4) return std::nullopt;
  m_.assign(static_cast<std::size_t>(w_) * h_, 0.0f);
  e_.assign(m_.size(), 0.0f);
  const float cw = static_cast<float>(std::sqrt(o.chroma_weight));
  const auto s = static_cast<float>(o.shade);
  const Yuv shaded = ball.Shaded(s);
  const float ball_y = shaded.y, ball_u = shaded.u, ball_v = shaded.v;
  const auto min_e = static_cast<float>(o.min_contrast * o.min_contrast);
  for (int y = y0_; y < y1; ++y) {
    for (int x = x0_; x < x1; ++x) {
      const float back = bg.Luma(x, y);
      const Yuv block = bg.Block(x / 2, y / 2);
      const float cy = ball_y - back, cu = cw * (ball_u - block.u), cv = cw * (ball_v - block.v);
      const float e = cy * cy + cu * cu + cv * cv;
      if (e < min_e) continue;
      uint8_t u = 128, v = 128;
      internal::ChromaAt(image, x, y, &u, &v);
      const float dy = internal::LumaAt(image, x, y) - back, du = cw * (u - block.u),
                  dv = cw * (v - block.v);
      const std::size_t k = static_cast<std::size_t>(y - y0_) * w_ + (x - x0_);
      m_[k] = dy * cy + du * cu + dv * cv;
      e_[k] = e;
    }
  }
  // The search: the middle on a coarse grid, every length and direction; then finer around the
  // best.
  const double dir_norm = std::hypot(dir_x, dir_y);
  const double base = dir_norm > 1e-9 ? std::atan2(dir_y, dir_x) : 0.0;
  struct Best {
    double score = -1e300, cx = 0, cy = 0, length = 0, angle = 0;
    Sums sums;
  } best;
  // The mean share of the ball in a streak of this length: the disc's area over the capsule's.
  const double disc = M_PI * r * r;
  const auto expected_share = [&](double length) { return disc / (length * diameter_px + disc); };
  // A pixel of a streak is at most a few times its mean share ball: what differs more (a player,
  // a line) counts only as much.
  const auto clip = [&](double length) { return o.max_pixel_share * expected_share(length); };
  const auto consider = [&](double cx, double cy, double length, double angle) {
    const Sums t =
        Template(cx, cy, std::cos(angle), std::sin(angle), length, -1.0, r, clip(length));
    const double score = Score(t);
    if (score > best.score) best = {score, cx, cy, length, angle, t};
  };
  const int steps = static_cast<int>(std::floor(o.search_px / o.coarse_step_px));
  const auto angle_step = [&](double length) {
    return std::atan2(o.angle_step_px, std::max(0.5 * length, diameter_px));
  };
  // Coarse: integer middles, each template a list of pixel offsets (no interpolation).
  const int cx0 = static_cast<int>(std::lround(mid_x)), cy0 = static_cast<int>(std::lround(mid_y));
  for (double share : o.length_shares) {
    const double length = share * max_length_px;
    const double da = angle_step(length);
    const int middle = (o.angles - 1) / 2;  // the predicted direction's index
    const double limit = clip(length);
    for (int a = 0; a < o.angles; ++a) {
      const double angle = base + static_cast<double>(a - middle) * da;
      BuildShape(std::cos(angle), std::sin(angle), length, r);
      for (int j = -steps; j <= steps; ++j) {
        for (int i = -steps; i <= steps; ++i) {
          const int cx = cx0 + static_cast<int>(std::lround(i * o.coarse_step_px));
          const int cy = cy0 + static_cast<int>(std::lround(j * o.coarse_step_px));
          const Sums t = ShapeSums(cx, cy, limit);
          const double score = Score(t);
          if (score > best.score)
            best = {score, static_cast<double>(cx), static_cast<double>(cy), length, angle, t};
        }
      }
    }
  }
  if (!(best.score > 0.0)) return std::nullopt;
  {
    const Best coarse = best;
    const double fine = 0.25 * o.coarse_step_px;
    const double da = angle_step(coarse.length);
    // Lengths between the coarse ones too: a template shorter than the streak slides along it.
    for (double scale : {0.85, 1.0, 1.2}) {
      for (int a = -1; a <= 1; ++a) {
        for (int j = -2; j <= 2; ++j) {
          for (int i = -2; i <= 2; ++i) {
            consider(coarse.cx + i * fine, coarse.cy + j * fine,
                     std::min(max_length_px, scale * coarse.length), coarse.angle + 0.5 * a * da);
          }
        }
      }
    }
  }
  // The null: the best template laid over the window away from it.
  const double ux = std::cos(best.angle), uy = std::sin(best.angle);
  BuildShape(ux, uy, best.length, r);
  const double null_limit = clip(best.length);
  null_.clear();
  const int side = static_cast<int>(std::ceil(std::sqrt(2.0 * o.null_samples)));
  const double spacing = 2.0 * o.null_reach_px / side;
  for (int j = 0; j <= side; ++j) {
    for (int i = 0; i <= side; ++i) {
      const double dx = -o.null_reach_px + i * spacing, dy = -o.null_reach_px + j * spacing;
      const double along = dx * ux + dy * uy, across = -dx * uy + dy * ux;
      if (std::abs(along) < best.length + diameter_px + 2.0 &&
          std::abs(across) < diameter_px + 4.0) {
        continue;  // overlaps the streak found
      }
      const Sums t = ShapeSums(static_cast<int>(std::lround(best.cx + dx)),
                               static_cast<int>(std::lround(best.cy + dy)), null_limit);
      if (t.n == 0) continue;  // reaches outside the window
      null_.push_back(Score(t));
    }
  }
  if (static_cast<int>(null_.size()) < o.null_samples / 2) return std::nullopt;
  const double median = MedianInPlace(null_);
  const double spread = std::max(RobustSigmaInPlace(null_, median), 1e-6);
  StreakHit hit;
  hit.cx = best.cx, hit.cy = best.cy, hit.length_px = best.length, hit.angle = best.angle;
  hit.snr = (best.score - median) / spread;
  if (hit.snr < o.min_snr) return std::nullopt;
  // A streak: its mean share is what the disc smeared over its length gives, the ring is clear.
  hit.share = best.sums.e > 0.0 ? best.sums.m / best.sums.e : 0.0;
  hit.expected_share = expected_share(best.length);
  if (hit.share < o.min_share_ratio * hit.expected_share ||
      hit.share > o.max_share_ratio * hit.expected_share) {
    return std::nullopt;
  }
  // The length and the middle from the moments along the streak: the best flat template leaves
  // out the dim ends (the disc's ramps), so its own length is short by about a diameter. A disc
  // of d px smeared over L px has a variance of L^2 / 12 + d^2 / 16 along its path.
  {
    double sw = 0.0, st = 0.0, stt = 0.0;
    const double half = 0.5 * best.length + diameter_px;
    const double limit = clip(best.length);
    for (int i = -static_cast<int>(std::ceil(half)); i <= static_cast<int>(std::ceil(half)); ++i) {
      for (int j = -static_cast<int>(std::ceil(r)); j <= static_cast<int>(std::ceil(r)); ++j) {
        if (std::abs(j) > r) continue;
        const double x = best.cx + i * ux - j * uy - x0_, y = best.cy + i * uy + j * ux - y0_;
        const int xi = static_cast<int>(std::lround(x)), yi = static_cast<int>(std::lround(y));
        if (xi < 0 || yi < 0 || xi >= w_ || yi >= h_) continue;
        const std::size_t k = static_cast<std::size_t>(yi) * w_ + xi;
        const double w = std::clamp(static_cast<double>(m_[k]), 0.0, limit * e_[k]);
        sw += w, st += w * i, stt += w * i * i;
      }
    }
    if (sw > 0.0) {
      const double mean = st / sw, var = stt / sw - mean * mean;
      const double length =
          std::sqrt(std::max(0.0, 12.0 * (var - diameter_px * diameter_px / 16.0)));
      hit.length_px = std::min(max_length_px, std::max(best.length, length));
      // The middle too: the flat template can sit off the streak's middle where one end lies over
      // something that differs strongly (a white line the ball darkens: 6 px in the test).
      hit.cx += mean * ux, hit.cy += mean * uy;
    }
  }
  const Sums ring = Template(best.cx, best.cy, ux, uy, best.length, r + 1.0, r + 2.5, 1e9);
  hit.ring_share = ring.e > 0.0 ? ring.m / ring.e : 0.0;
  if (hit.ring_share > o.max_ring_ratio * hit.share) return std::nullopt;
  hit.colour_residual = ColourResidual(image, bg, ball, hit, diameter_px, o);
  return hit;
}

}  // namespace p4::segment
