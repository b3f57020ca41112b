#include "p4/segment/foreground_finder.h"

#include <algorithm>
#include <cmath>

#include "p4/segment/pixel_access.h"
#include "p4/segment/union_find.h"

namespace p4::segment {
namespace {

using internal::LumaAt;

// Does the colour tables' class mask take pixel (x, y)?
inline bool InTables(const ImageView& image, const ColorLut& lut, uint32_t mask, int x, int y) {
  uint8_t u = 128, v = 128;
  internal::ChromaAt(image, x, y, &u, &v);
  return (lut.Classify(LumaAt(image, x, y), u, v) & mask) != 0;
}

// A block's colour, the background's there, and their distance (sigmas squared).
struct BlockLook {
  Yuv seen, model;
  double distance2 = 0.0;
};

BlockLook LookAt(const ImageView& image, const BackgroundModel& bg, int bx, int by) {
  BlockLook look{BackgroundModel::BlockOf(image, bx, by), bg.Block(bx, by)};
  look.distance2 = bg.Distance2(look.seen, look.model, bx, by);
  return look;
}

// Is this block the ball (any share, any shading) over its background?
bool BallBlock(const BlockLook& look, const BackgroundModel& bg, const BallColour& ball, int bx,
               int by, const ForegroundOptions& o, double k2, Unmixed* u) {
  if (look.distance2 <= k2) return false;
  *u = Unmix(look.seen, look.model, ball, o.unmix);
  if (u->alpha < o.min_alpha || u->alpha > o.max_alpha) return false;
  const double sigma = std::hypot(bg.SigmaLuma(bx, by),
                                  std::sqrt(2.0 * o.unmix.chroma_weight) * bg.SigmaChroma(bx, by));
  return u->residual <= std::max(o.max_residual_share * u->difference, o.residual_sigmas * sigma);
}

}  // namespace

bool ForegroundOptions::IsValid(std::string* error) const {
  if (!(min_alpha > 0.0 && max_alpha > min_alpha) || !(max_residual_share > 0.0) ||
      !(residual_sigmas >= 0.0) || max_regions < 1 || !(min_luma_contrast >= 0.0)) {
    if (error) *error = "foreground: need 0 < min alpha < max alpha, positive bounds";
    return false;
  }
  return unmix.IsValid(error);
}

bool DiscSearchOptions::IsValid(std::string* error) const {
  if (!(ring_share >= 0.0) || !(min_ring_px > 0.0) || !(min_fill > 0.0 && min_fill <= 1.0) ||
      !(min_contrast >= 0.0) || refine_iterations < 0) {
    if (error) *error = "disc search: need a positive ring, 0 < min fill <= 1, contrast >= 0";
    return false;
  }
  return true;
}

int ForegroundFinder::Find(const ImageView& image, const BackgroundModel& bg,
                           const BallColour& ball, const Roi& roi_in,
                           const ForegroundOptions& options, std::vector<CoverageRegion>* out) {
  out->clear();
  runs_.clear();
  const Roi roi =
      roi_in.empty() ? Roi{0, 0, bg.width(), bg.height()} : roi_in.Clipped(bg.width(), bg.height());
  if (roi.empty()) return 0;
  const int bx0 = roi.x0 / 2, bx1 = (roi.x1 + 1) / 2, by0 = roi.y0 / 2, by1 = (roi.y1 + 1) / 2;
  const double k = bg.options().foreground_sigmas;
  const double k2 = k * k;
  std::size_t above_begin = 0, above_end = 0;
  Unmixed u;
  for (int by = by0; by < std::min(by1, bg.height() / 2); ++by) {
    const std::size_t row_begin = runs_.size();
    int open = -1;
    for (int bx = bx0; bx <= std::min(bx1, bg.width() / 2); ++bx) {
      const bool in = bx < std::min(bx1, bg.width() / 2) &&
                      BallBlock(LookAt(image, bg, bx, by), bg, ball, bx, by, options, k2, &u);
      if (in && open < 0) open = bx;
      if (!in && open >= 0) {
        const int index = static_cast<int>(runs_.size());
        runs_.push_back({by, open, bx, index});
        open = -1;
      }
    }
    internal::JoinWithRowAbove(runs_, above_begin, above_end, row_begin);
    above_begin = row_begin;
    above_end = runs_.size();
  }
  // Each region's block box, then its coverage measure.
  struct Box {
    int x0, y0, x1, y1, blocks;
  };
  std::vector<Box> boxes(runs_.size(), Box{0, 0, 0, 0, 0});
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const Run& r = runs_[i];
    Box& b = boxes[static_cast<std::size_t>(internal::FindRoot(runs_, static_cast<int>(i)))];
    if (b.blocks == 0) {
      b = {r.x0, r.y, r.x1, r.y + 1, 0};
    } else {
      b.x0 = std::min(b.x0, r.x0), b.x1 = std::max(b.x1, r.x1);
      b.y0 = std::min(b.y0, r.y), b.y1 = std::max(b.y1, r.y + 1);
    }
    b.blocks += r.x1 - r.x0;
  }
  std::vector<Box> regions;
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    if (runs_[i].parent == static_cast<int>(i)) regions.push_back(boxes[i]);
  }
  std::sort(regions.begin(), regions.end(),
            [](const Box& a, const Box& b) { return a.blocks > b.blocks; });
  for (const Box& b : regions) {
    if (static_cast<int>(out->size()) >= options.max_regions) break;
    if (b.blocks > options.max_blocks) continue;
    // The blocks' pixels and one block around them (the ball's anti-aliased, blurred edge).
    const Roi window = Roi{2 * b.x0 - 2, 2 * b.y0 - 2, 2 * b.x1 + 2, 2 * b.y1 + 2}.Clipped(
        bg.width(), bg.height());
    CoverageRegion measured;
    if (Measure(image, bg, ball, window, options, &measured) &&
        measured.region.major_diameter <=
            options.max_elongation * std::max(1.0, measured.region.minor_diameter) &&
        measured.region.diameter >= options.min_diameter_px &&
        measured.region.diameter <= options.max_diameter_px) {
      measured.blocks = b.blocks;
      out->push_back(measured);
    }
  }
  std::sort(out->begin(), out->end(), [](const CoverageRegion& a, const CoverageRegion& b) {
    return a.roundness > b.roundness;
  });
  return static_cast<int>(out->size());
}

ForegroundFinder::BlockRange ForegroundFinder::BlocksOf(const Roi& roi, const BackgroundModel& bg) {
  return {std::max(0, roi.x0 / 2), std::max(0, roi.y0 / 2),
          std::min(bg.width() / 2, (roi.x1 + 1) / 2), std::min(bg.height() / 2, (roi.y1 + 1) / 2)};
}

int ForegroundFinder::CountDiffering(const ImageView& image, const BackgroundModel& bg,
                                     const BlockRange& range, double sigmas, uint8_t* out) {
  const int bw = bg.width() / 2;
  const double k2 = sigmas * sigmas;
  int differ = 0;
  for (int by = range.y0; by < range.y1; ++by) {
    for (int bx = range.x0; bx < range.x1; ++bx) {
      const bool d = bg.BlockDistance2(image, bx, by) > k2;
      differ += d;
      if (out) out[static_cast<std::size_t>(by) * bw + bx] = d;
    }
  }
  return differ;
}

BlockMask ForegroundFinder::DifferingBlocks(const ImageView& image, const BackgroundModel& bg,
                                            const Roi& roi_in, double sigmas, bool grow) {
  const Roi roi = roi_in.empty() ? Roi{0, 0, image.width, image.height} : roi_in;
  const int bw = bg.width() / 2, bh = bg.height() / 2;
  const BlockRange range{std::max(0, roi.x0 / 2 - 1), std::max(0, roi.y0 / 2 - 1),
                         std::min(bw, (roi.x1 + 1) / 2 + 1), std::min(bh, (roi.y1 + 1) / 2 + 1)};
  CompareBlocks(image, bg, range, sigmas);
  GrowMask(bg, range, grow);
  return BlockMask{mask_.data(), bw, bh};
}

double ForegroundFinder::DifferingShare(const ImageView& image, const BackgroundModel& bg,
                                        const Roi& roi, double sigmas) {
  const BlockRange range = BlocksOf(roi, bg);
  if (range.size() == 0) return 0.0;
  return static_cast<double>(CountDiffering(image, bg, range, sigmas, nullptr)) / range.size();
}

BlockMask ForegroundFinder::DifferingBlocksWithin(const ImageView& image, const BackgroundModel& bg,
                                                  std::span<const Roi> within, double sigmas,
                                                  bool grow, double max_share,
                                                  std::vector<Roi>* taken) {
  const int bw = bg.width() / 2, bh = bg.height() / 2;
  mask_.assign(static_cast<std::size_t>(bw) * bh, 1);
  for (const Roi& roi : within) {
    // Each window's blocks compared once: for its share and for the mask.
    const BlockRange range = BlocksOf(roi, bg);
    const int differ = CompareBlocks(image, bg, range, sigmas);
    const double share = range.size() == 0 ? 0.0 : static_cast<double>(differ) / range.size();
    if (share > max_share) continue;
    GrowMask(bg, range, grow);
    if (taken) taken->push_back(roi);
  }
  return BlockMask{mask_.data(), bw, bh};
}

int ForegroundFinder::CompareBlocks(const ImageView& image, const BackgroundModel& bg,
                                    const BlockRange& range, double sigmas) {
  const std::size_t blocks = static_cast<std::size_t>(bg.width() / 2) * (bg.height() / 2);
  if (mask_.size() != blocks) mask_.assign(blocks, 0);
  if (differs_.size() != blocks) differs_.assign(blocks, 0);
  return CountDiffering(image, bg, range, sigmas, differs_.data());
}

void ForegroundFinder::GrowMask(const BackgroundModel& bg, const BlockRange& range, bool grow) {
  const int bw = bg.width() / 2;
  const int reach = grow ? 1 : 0;
  for (int by = range.y0; by < range.y1; ++by) {
    for (int bx = range.x0; bx < range.x1; ++bx) {
      uint8_t any = 0;
      for (int dy = -reach; dy <= reach && !any; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          const int x = bx + dx, y = by + dy;
          if (x >= range.x0 && x < range.x1 && y >= range.y0 && y < range.y1 &&
              differs_[static_cast<std::size_t>(y) * bw + x]) {
            any = 1;
            break;
          }
        }
      }
      mask_[static_cast<std::size_t>(by) * bw + bx] = any;
    }
  }
}

bool ForegroundFinder::FillCoverage(const ImageView& image, const BackgroundModel& bg,
                                    const BallColour& ball, const Roi& w,
                                    const ForegroundOptions& options, float* region_shade_out) {
  const int bx0 = w.x0 / 2, by0 = w.y0 / 2, bw = (w.x1 - w.x0) / 2, bh = (w.y1 - w.y0) / 2;
  // Per block: its shading and share when it is the ball; blocks next to the ball's that differ
  // only faintly are its edge; a block that differs with another colour is something else.
  block_shade_.assign(static_cast<std::size_t>(bw) * bh, -1.0f);
  block_alpha_.assign(block_shade_.size(), 0.0f);
  enum Kind : uint8_t { kNone, kBall, kFaint, kOther };
  kind_.assign(block_shade_.size(), kNone);
  std::vector<float>& block_alpha = block_alpha_;
  std::vector<uint8_t>& kind = kind_;
  double sum_a = 0.0, sum_as = 0.0;
  const double k2 = bg.options().foreground_sigmas * bg.options().foreground_sigmas;
  for (int j = 0; j < bh; ++j) {
    for (int i = 0; i < bw; ++i) {
      const std::size_t b = static_cast<std::size_t>(j) * bw + i;
      Unmixed u;
      const BlockLook look = LookAt(image, bg, bx0 + i, by0 + j);
      if (BallBlock(look, bg, ball, bx0 + i, by0 + j, options, k2, &u)) {
        kind[b] = kBall;
        block_alpha[b] = static_cast<float>(std::min(1.0, u.alpha));
        if (u.alpha > options.own_shade_alpha) {
          block_shade_[b] = static_cast<float>(u.shade);
        }
        // The region's shading, weighted by share (a blur streak's blocks are all faint).
        sum_a += u.alpha, sum_as += u.alpha * u.shade;
        continue;
      }
      if (look.distance2 <= 4.0) continue;  // within 2 sigmas: background
      kind[b] = look.distance2 <= k2 ? kFaint : kOther;
      if (kind[b] == kFaint) {
        // A faint edge: its share from its colour, for when the luma cannot tell.
        block_alpha[b] = static_cast<float>(
            std::clamp(Unmix(look.seen, look.model, ball, options.unmix).alpha, 0.0, 1.0));
      }
    }
  }
  // Faint blocks count only beside a ball block.
  counts_.assign(kind.size(), 0);
  std::vector<uint8_t>& counts = counts_;
  for (int j = 0; j < bh; ++j) {
    for (int i = 0; i < bw; ++i) {
      const std::size_t b = static_cast<std::size_t>(j) * bw + i;
      if (kind[b] == kBall) {
        counts[b] = 1;
        continue;
      }
      if (kind[b] != kFaint) continue;
      for (int dj = -1; dj <= 1 && !counts[b]; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          const int jj = j + dj, ii = i + di;
          if (jj >= 0 && jj < bh && ii >= 0 && ii < bw &&
              kind[static_cast<std::size_t>(jj) * bw + ii] == kBall) {
            counts[b] = 1;
            break;
          }
        }
      }
    }
  }
  // No ball block: nothing here is the ball. (Every ball block's share is at least min_alpha.)
  if (!(sum_a > 0.0)) return false;
  const auto region_shade = static_cast<float>(sum_as / sum_a);
  *region_shade_out = region_shade;
  // Per pixel: the ball's share from the luma, between the background's and the ball's at the
  // block's shading; where they are too alike, the block's share from its colour.
  const int pw = w.x1 - w.x0;
  alpha_.assign(static_cast<std::size_t>(pw) * (w.y1 - w.y0), 0.0f);
  for (int y = w.y0; y < w.y1; ++y) {
    const int j = (y - w.y0) / 2;
    for (int x = w.x0; x < w.x1; ++x) {
      const int i = (x - w.x0) / 2;
      const std::size_t b = static_cast<std::size_t>(j) * bw + i;
      if (!counts[b]) continue;
      float shade = block_shade_[b];
      if (shade <= 0.0f) {
        // A block without its own shading (an edge): its neighbours' (the ball's dark bottom
        // is darker than its middle), else the region's.
        float sum_shade = 0.0f;
        int n = 0;
        for (int dj = -1; dj <= 1; ++dj) {
          for (int di = -1; di <= 1; ++di) {
            const int jj = j + dj, ii = i + di;
            if (jj < 0 || jj >= bh || ii < 0 || ii >= bw) continue;
            const float s = block_shade_[static_cast<std::size_t>(jj) * bw + ii];
            if (s > 0.0f) sum_shade += s, ++n;
          }
        }
        shade = n ? sum_shade / n : region_shade;
      }
      const float ball_luma = ball.Shaded(shade).y;
      const float back = bg.Luma(x, y);
      const float contrast = ball_luma - back;
      double alpha;
      if (block_alpha[b] >= options.interior_alpha) {
        alpha = 1.0;  // inside the ball: all of it, however its shading varies in the block
      } else if (std::abs(contrast) >= options.min_luma_contrast) {
        alpha = (LumaAt(image, x, y) - back) / contrast;
      } else {
        alpha = block_alpha[b];
      }
      alpha = std::clamp(alpha, 0.0, 1.0);
      if (alpha < 0.05) continue;
      alpha_[static_cast<std::size_t>(y - w.y0) * pw + (x - w.x0)] = static_cast<float>(alpha);
    }
  }
  return true;
}

void ForegroundFinder::CountCore(const ImageView& image, const ForegroundOptions& options,
                                 const Roi& w, int x, int y, double alpha, CoreCount* count) const {
  // The core's colour is judged where the block's own colour says it is mostly ball: a small
  // streak's chroma (half resolution, smeared by the encoder) is the background's too.
  if (!options.lut || alpha < options.core_alpha) return;
  const std::size_t b =
      static_cast<std::size_t>((y - w.y0) / 2) * ((w.x1 - w.x0) / 2) + (x - w.x0) / 2;
  if (block_alpha_[b] < options.core_alpha) return;
  ++count->core;
  count->in_tables += InTables(image, *options.lut, options.lut_mask, x, y);
}

bool ForegroundFinder::CoreNotBall(const ForegroundOptions& options, const CoreCount& count) {
  return options.lut && count.core >= options.core_min_pixels &&
         count.in_tables < options.core_share * count.core;
}

bool ForegroundFinder::Measure(const ImageView& image, const BackgroundModel& bg,
                               const BallColour& ball, const Roi& window_in,
                               const ForegroundOptions& options, CoverageRegion* out) {
  const Roi w =
      Roi{window_in.x0 & ~1, window_in.y0 & ~1, (window_in.x1 + 1) & ~1, (window_in.y1 + 1) & ~1}
          .Clipped(bg.width(), bg.height());
  if (w.empty()) return false;
  float region_shade = 1.0f;
  if (!FillCoverage(image, bg, ball, w, options, &region_shade)) return false;
  const int pw = w.x1 - w.x0;
  double sum = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  CoreCount core;
  int x0 = w.x1, y0 = w.y1, x1 = w.x0, y1 = w.y0;
  for (int y = w.y0; y < w.y1; ++y) {
    for (int x = w.x0; x < w.x1; ++x) {
      const double alpha = alpha_[static_cast<std::size_t>(y - w.y0) * pw + (x - w.x0)];
      if (alpha <= 0.0) continue;
      CountCore(image, options, w, x, y, alpha, &core);
      sum += alpha;
      sx += alpha * x, sy += alpha * y;
      sxx += alpha * x * x, syy += alpha * y * y, sxy += alpha * x * y;
      x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1),
      y1 = std::max(y1, y + 1);
    }
  }
  if (sum < 0.5) return false;
  CoverageRegion& r = *out;
  r = CoverageRegion{};
  r.coverage = sum;
  r.shade = region_shade;
  Region& g = r.region;
  g.cx = sx / sum;
  g.cy = sy / sum;
  g.area = static_cast<int>(std::lround(sum));
  g.x0 = x0, g.y0 = y0, g.x1 = x1, g.y1 = y1;
  g.diameter = 2.0 * std::sqrt(sum / M_PI);
  // Moments of the coverage (each pixel adds 1/12 of its own extent).
  const double cxx = sxx / sum - g.cx * g.cx + 1.0 / 12.0;
  const double cyy = syy / sum - g.cy * g.cy + 1.0 / 12.0;
  const double cxy = sxy / sum - g.cx * g.cy;
  const MomentDiameters d = DiametersFromMoments(cxx, cyy, cxy);
  g.minor_diameter = d.minor;
  g.major_diameter = d.major;
  g.touches_border = x0 == 0 || y0 == 0 || x1 == bg.width() || y1 == bg.height();
  // A disc of diameter D smeared over a length L: variance D^2/16 across, D^2/16 + L^2/12 along.
  const double along = d.major * d.major / 16.0, across = g.diameter * g.diameter / 16.0;
  r.streak_px = std::sqrt(std::max(0.0, 12.0 * (along - across)));
  // A round region (not a blur streak) shows the ball's own colour in its core: the colour
  // tables must agree with part of it (skin and shirts unmix as a shaded ball, the tables say no).
  if (d.major < options.core_max_elongation * d.minor && CoreNotBall(options, core)) return false;
  // The ellipse of the moments (semi-axes 2 sqrt(lambda)) has area pi minor major / 4.
  r.roundness = std::min(1.0, Roundness(sum, d.minor, d.major));
  r.streak_angle = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  return true;
}

bool ForegroundFinder::FindDisc(const ImageView& image, const BackgroundModel& bg,
                                const BallColour& ball, double cx, double cy, double search_px,
                                double diameter_px, const ForegroundOptions& options,
                                const DiscSearchOptions& disc, CoverageRegion* out) {
  if (!(diameter_px > 0.0) || !(search_px >= 0.0)) return false;
  const double radius = 0.5 * diameter_px;
  const double ring = std::max(disc.min_ring_px, disc.ring_share * diameter_px);
  const int reach = static_cast<int>(std::ceil(search_px + radius + ring)) + 2;
  const int ix = static_cast<int>(std::lround(cx)), iy = static_cast<int>(std::lround(cy));
  const Roi w =
      Roi{(ix - reach) & ~1, (iy - reach) & ~1, (ix + reach + 2) & ~1, (iy + reach + 2) & ~1}
          .Clipped(bg.width(), bg.height());
  if (w.empty()) return false;
  float region_shade = 1.0f;
  if (!FillCoverage(image, bg, ball, w, options, &region_shade)) return false;
  const int pw = w.x1 - w.x0;
  const auto alpha_at = [&](int x, int y) {
    return alpha_[static_cast<std::size_t>(y - w.y0) * pw + (x - w.x0)];
  };
  // The disc's and the ring's pixel offsets about a whole-pixel centre.
  std::vector<std::pair<int, int>> inside, around;
  const int outer = static_cast<int>(std::ceil(radius + ring));
  for (int dy = -outer; dy <= outer; ++dy) {
    for (int dx = -outer; dx <= outer; ++dx) {
      const double d2 = dx * dx + dy * dy;
      if (d2 <= radius * radius) {
        inside.emplace_back(dx, dy);
      } else if (d2 <= (radius + ring) * (radius + ring)) {
        around.emplace_back(dx, dy);
      }
    }
  }
  if (inside.empty() || around.empty()) return false;
  // The best whole-pixel centre whose ring lies in the window: the disc's mean share less the
  // ring's (nearest to the guess among equals).
  // (A large ball on a grid of a tenth of its diameter: the refinement below centres it.)
  const int s = static_cast<int>(std::floor(search_px));
  const int step = std::max(1, static_cast<int>(diameter_px / 10.0));
  double best = -2.0, best_fill = 0.0, best_d2 = 0.0;
  int bx = 0, by = 0;
  for (int y = iy - s; y <= iy + s; y += step) {
    for (int x = ix - s; x <= ix + s; x += step) {
      const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      if (d2 > search_px * search_px + 0.5) continue;
      if (x - outer < w.x0 || y - outer < w.y0 || x + outer >= w.x1 || y + outer >= w.y1) {
        continue;
      }
      double in = 0.0, rim = 0.0;
      for (const auto& [dx, dy] : inside) in += alpha_at(x + dx, y + dy);
      for (const auto& [dx, dy] : around) rim += alpha_at(x + dx, y + dy);
      const double fill = in / static_cast<double>(inside.size());
      const double score = fill - rim / static_cast<double>(around.size());
      if (score > best + 1e-9 || (std::abs(score - best) <= 1e-9 && d2 < best_d2)) {
        best = score, best_fill = fill, best_d2 = d2, bx = x, by = y;
      }
    }
  }
  if (best_fill < disc.min_fill || best < disc.min_contrast) return false;
  // The centre by the coverage within the disc (its pixels whose centres lie within the radius:
  // a ring half a pixel wider takes in what meets the ball, and leans to it), from the best whole
  // pixel.
  double mx = bx, my = by, sum = 0.0;
  int x0 = w.x1, y0 = w.y1, x1 = w.x0, y1 = w.y0;
  CoreCount core;
  const double r2 = radius * radius;
  for (int it = 0; it <= disc.refine_iterations; ++it) {
    const bool last = it == disc.refine_iterations;
    double sx = 0.0, sy = 0.0;
    sum = 0.0;
    for (int y = std::max(w.y0, static_cast<int>(std::floor(my - radius - 1)));
         y <= std::min(w.y1 - 1, static_cast<int>(std::ceil(my + radius + 1))); ++y) {
      for (int x = std::max(w.x0, static_cast<int>(std::floor(mx - radius - 1)));
           x <= std::min(w.x1 - 1, static_cast<int>(std::ceil(mx + radius + 1))); ++x) {
        if ((x - mx) * (x - mx) + (y - my) * (y - my) > r2) continue;
        const double a = alpha_at(x, y);
        if (a <= 0.0) continue;
        sum += a, sx += a * x, sy += a * y;
        if (!last) continue;
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1),
        y1 = std::max(y1, y + 1);
        CountCore(image, options, w, x, y, a, &core);
      }
    }
    if (sum < 0.5) return false;
    if (!last) mx = sx / sum, my = sy / sum;
  }
  // The core shows the ball's colour, as Measure's round regions must.
  if (CoreNotBall(options, core)) return false;
  CoverageRegion& r = *out;
  r = CoverageRegion{};
  r.coverage = sum;
  r.shade = region_shade;
  r.roundness = best_fill;
  Region& g = r.region;
  g.cx = mx;
  g.cy = my;
  g.area = static_cast<int>(std::lround(sum));
  g.x0 = x0, g.y0 = y0, g.x1 = x1, g.y1 = y1;
  g.diameter = 2.0 * std::sqrt(sum / M_PI);
  g.minor_diameter = g.major_diameter = diameter_px;
  g.touches_border = x0 == 0 || y0 == 0 || x1 == bg.width() || y1 == bg.height();
  return true;
}

}  // namespace p4::segment
