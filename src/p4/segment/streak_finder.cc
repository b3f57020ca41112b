#include "p4/segment/streak_finder.h"

#include <algorithm>
#include <cmath>

namespace p4::segment {

namespace {

// A family of parallel lines over the cell grid: along x (or y when `along_y`), the other
// coordinate moving by round(slope * t) at step t. Every cell lies on exactly one line.
struct Direction {
  bool along_y = false;
  double slope = 0.0;
};

constexpr double kTan22 = 0.41421356237309503;
constexpr Direction kDirections[] = {{false, 0.0},   {false, kTan22}, {false, 1.0},
                                     {true, kTan22}, {true, 0.0},     {true, -kTan22},
                                     {false, -1.0},  {false, -kTan22}};

int Step(const Direction& d, int t) { return static_cast<int>(std::lround(d.slope * t)); }

// The share of the blocks whose centres lie `inner` to `outer` px from the candidate's segment
// that differ from the background by more than its foreground sigmas (0 when there are none).
double DifferingShareAround(const ImageView& image, const BackgroundModel& bg,
                            const StreakCandidate& c, double inner, double outer) {
  const double ux = std::cos(c.angle), uy = std::sin(c.angle), half = 0.5 * c.length_px;
  const double reach = half + outer;
  const double k2 = bg.options().foreground_sigmas * bg.options().foreground_sigmas;
  // Block (bx, by) covers pixels 2bx..2bx+1: its centre is at 2bx + 0.5.
  const int bx0 = std::max(0, static_cast<int>(std::floor((c.cx - reach) / 2.0))),
            bx1 = std::min(bg.width() / 2 - 1, static_cast<int>(std::ceil((c.cx + reach) / 2.0))),
            by0 = std::max(0, static_cast<int>(std::floor((c.cy - reach) / 2.0))),
            by1 = std::min(bg.height() / 2 - 1, static_cast<int>(std::ceil((c.cy + reach) / 2.0)));
  int ring = 0, differ = 0;
  for (int by = by0; by <= by1; ++by) {
    for (int bx = bx0; bx <= bx1; ++bx) {
      const double px = 2.0 * bx + 0.5 - c.cx, py = 2.0 * by + 0.5 - c.cy;
      const double along = std::clamp(px * ux + py * uy, -half, half);
      const double distance = std::hypot(px - along * ux, py - along * uy);
      if (distance <= inner || distance > outer) continue;
      ++ring;
      differ += bg.BlockDistance2(image, bx, by) > k2;
    }
  }
  return ring > 0 ? static_cast<double>(differ) / ring : 0.0;
}

}  // namespace

bool StreakFinderOptions::IsValid(std::string* error) const {
  const bool halves_ok = !half_cells.empty() && std::all_of(half_cells.begin(), half_cells.end(),
                                                            [](int h) { return h >= 1; });
  if (!halves_ok || side_cells < 1 || cell_blocks < 1 || !(max_share > 0.0) || !(min_score > 0.0) ||
      max_candidates < 1 || max_seen < max_candidates || !(still_px >= 0.0) || !(shade > 0.0) ||
      !(min_contrast >= 0.0) || !(chroma_weight >= 0.0)) {
    if (error) {
      *error =
          "streak finder: cells, half-lengths and side offset of at least one; positive share, "
          "score, candidates (no more than the local bests kept) and shading";
    }
    return false;
  }
  if (!(isolated_inner_px >= 0.0) || !(isolated_outer_px > isolated_inner_px) ||
      !(isolated_max_share <= 1.0)) {
    if (error) {
      *error =
          "streak finder: the isolation ring needs 0 <= inner < outer (px) and a share of at "
          "most 1";
    }
    return false;
  }
  return true;
}

int StreakFinder::Find(const ImageView& image, const BackgroundModel& bg, const BallColour& ball,
                       const StreakFinderOptions& o, std::vector<StreakCandidate>* out) {
  out->clear();
  if (!bg.ready()) return 0;
  // Cells of cell_blocks x cell_blocks blocks: a line one cell wide holds a ball of 3-6 px.
  const int cb = o.cell_blocks, cell_px = 2 * cb;
  bw_ = bg.width() / cell_px, bh_ = bg.height() / cell_px;
  const std::size_t cells = static_cast<std::size_t>(bw_) * bh_;
  m_.assign(cells, 0.0f);
  v_.assign(cells, 0.0f);
  const auto w = static_cast<float>(o.chroma_weight);
  const auto s = static_cast<float>(o.shade);
  const Yuv shaded = ball.Shaded(s);
  const auto min_e = static_cast<float>(o.min_contrast * o.min_contrast);
  const auto clip = static_cast<float>(o.max_share);
  for (int by = 0; by < bh_ * cb; ++by) {
    for (int bx = 0; bx < bw_ * cb; ++bx) {
      const Yuv back = bg.Block(bx, by);
      const float cy = shaded.y - back.y, cu = shaded.u - back.u, cv = shaded.v - back.v;
      const float e = cy * cy + w * (cu * cu + cv * cv);
      if (e < min_e) continue;
      const Yuv seen = BackgroundModel::BlockOf(image, bx, by);
      const float m =
          (seen.y - back.y) * cy + w * ((seen.u - back.u) * cu + (seen.v - back.v) * cv);
      const float sy = bg.SigmaLuma(bx, by), sc = bg.SigmaChroma(bx, by);
      const std::size_t k = static_cast<std::size_t>(by / cb) * bw_ + bx / cb;
      m_[k] += std::clamp(m, -clip * e, clip * e);
      v_[k] += sy * sy * cy * cy + w * w * sc * sc * (cu * cu + cv * cv);
    }
  }
  best_.assign(cells, 0.0f);
  best_dir_.assign(cells, -1);
  best_half_.assign(cells, 0);
  pm_.resize(cells);
  pv_.resize(cells);
  for (int di = 0; di < static_cast<int>(std::size(kDirections)); ++di) {
    const Direction& d = kDirections[di];
    // (t, u): t along the line, u across. The prefix sums are stored t-major (pm_[t * nu + u]);
    // a cell's index in the grid is image_index(t, u).
    const int nt = d.along_y ? bh_ : bw_, nu = d.along_y ? bw_ : bh_;
    const auto image_index = [&](int t, int u) {
      return d.along_y ? static_cast<std::size_t>(t) * bw_ + u
                       : static_cast<std::size_t>(u) * bw_ + t;
    };
    step_.resize(static_cast<std::size_t>(nt) + 1);
    for (int t = -1; t < nt; ++t) step_[t + 1] = Step(d, t);
    const auto step = [&](int t) { return step_[static_cast<std::size_t>(t) + 1]; };
    // Prefix sums along each line (a line enters and leaves the grid once: its slope is fixed).
    for (int t = 0; t < nt; ++t) {
      const int shift = t > 0 ? step(t) - step(t - 1) : 0;
      float* row_m = &pm_[static_cast<std::size_t>(t) * nu];
      float* row_v = &pv_[static_cast<std::size_t>(t) * nu];
      const float* prev_m = t > 0 ? row_m - nu : nullptr;
      const float* prev_v = t > 0 ? row_v - nu : nullptr;
      for (int u = 0; u < nu; ++u) {
        const std::size_t k = image_index(t, u);
        const int up = u - shift;
        const bool continues = prev_m && up >= 0 && up < nu;
        row_m[u] = (continues ? prev_m[up] : 0.0f) + m_[k];
        row_v[u] = (continues ? prev_v[up] : 0.0f) + v_[k];
      }
    }
    line_m_.resize(static_cast<std::size_t>(nu));
    line_v_.resize(static_cast<std::size_t>(nu));
    score_.resize(static_cast<std::size_t>(nu));
    for (const int h : o.half_cells) {
      for (int t = h; t + h < nt; ++t) {
        // The segment of the line through (t, u) from t - h to t + h: its end at (t + h,
        // u + du1), the cell before its start at (t - h - 1, u + du0) (none before the grid);
        // it stays in the grid when its first and last cells do (the steps are monotonic).
        const int du1 = step(t + h) - step(t), du0 = step(t - h - 1) - step(t);
        const int dus = step(t - h) - step(t);
        const int lo = std::max(0, -std::min(du1, dus)), hi = std::min(nu, nu - std::max(du1, dus));
        const bool from_start = t - h - 1 < 0;
        const float* end_m = &pm_[static_cast<std::size_t>(t + h) * nu];
        const float* end_v = &pv_[static_cast<std::size_t>(t + h) * nu];
        const float* before_m =
            from_start ? nullptr : &pm_[static_cast<std::size_t>(t - h - 1) * nu];
        const float* before_v =
            from_start ? nullptr : &pv_[static_cast<std::size_t>(t - h - 1) * nu];
        for (int u = lo; u < hi; ++u) {
          const int ub = u + du0;
          if (!from_start && (ub < 0 || ub >= nu)) {
            line_m_[u] = 0.0f, line_v_[u] = -1.0f;  // marks a segment that leaves the grid
            continue;
          }
          line_m_[u] = end_m[u + du1] - (from_start ? 0.0f : before_m[ub]);
          line_v_[u] = end_v[u + du1] - (from_start ? 0.0f : before_v[ub]);
        }
        // The scores (squared) of this step's segments, branch-free (the signs are noise; the
        // compiler vectorises it): a segment that leaves the grid, or whose sides do, scores 0.
        const int side = o.side_cells;
        const float* __restrict lm = line_m_.data();
        const float* __restrict lv = line_v_.data();
        float* __restrict sc = score_.data();
        for (int u = lo + side; u < hi - side; ++u) {
          const float side_m = std::max(0.0f, std::max(lm[u - side], lm[u + side]));
          const float side_v = std::max(lv[u - side], lv[u + side]);
          const float v = lv[u];
          const bool valid = v > 0.0f && lv[u - side] >= 0.0f && lv[u + side] >= 0.0f;
          // The score squared (its sign kept): no square root in the loop.
          const float excess = lm[u] - side_m;
          const float score2 = excess * std::abs(excess) / std::max(v + side_v, 1e-6f);
          sc[u] = valid ? score2 : 0.0f;
        }
        for (int u = lo + side; u < hi - side; ++u) {
          if (!(sc[u] > 0.0f)) continue;
          const std::size_t k = image_index(t, u);
          if (sc[u] > best_[k]) best_[k] = sc[u], best_dir_[k] = di, best_half_[k] = h;
        }
      }
    }
  }
  const auto min_score2 = static_cast<float>(o.min_score * o.min_score);
  // The cells' best segments, best first.
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < cells; ++k) {
    if (best_[k] >= min_score2) order.push_back(k);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return best_[a] > best_[b] || (best_[a] == best_[b] && a < b);
  });
  // Every segment apart from the better ones is a local best (`seen`); those at a place where
  // one was in the last frame stay out (a lamp, a line, a player's edge: the ball in play never
  // leaves two streaks at one place), so the candidates go to what is new, but for those the
  // hall around stands still for (the ball slowing at the top of a toss).
  std::vector<StreakCandidate> seen;
  for (const std::size_t k : order) {
    const Direction& d = kDirections[best_dir_[k]];
    const double step = std::hypot(1.0, d.slope);
    StreakCandidate c;
    const std::size_t row = k / static_cast<std::size_t>(bw_);
    c.cx = cell_px * static_cast<double>(k - row * bw_) + 0.5 * (cell_px - 1);
    c.cy = cell_px * static_cast<double>(row) + 0.5 * (cell_px - 1);
    c.length_px = cell_px * (2 * best_half_[k] + 1) * step;
    double angle = d.along_y ? std::atan2(1.0, d.slope) : std::atan2(d.slope, 1.0);
    if (angle < 0.0) angle += M_PI;
    c.angle = angle;
    c.score = std::sqrt(best_[k]);
    const bool apart = std::none_of(seen.begin(), seen.end(), [&](const StreakCandidate& a) {
      return std::hypot(a.cx - c.cx, a.cy - c.cy) < 0.5 * (a.length_px + c.length_px) + 4.0;
    });
    if (!apart) continue;
    seen.push_back(c);
    const bool still = std::any_of(last_seen_.begin(), last_seen_.end(), [&](const auto& a) {
      return std::hypot(a.cx - c.cx, a.cy - c.cy) <= o.still_px;
    });
    if (!still || (o.isolated_max_share >= 0.0 &&
                   DifferingShareAround(image, bg, c, o.isolated_inner_px, o.isolated_outer_px) <=
                       o.isolated_max_share)) {
      out->push_back(c);
    }
    if (static_cast<int>(out->size()) >= o.max_candidates ||
        static_cast<int>(seen.size()) >= o.max_seen) {
      break;
    }
  }
  last_seen_ = std::move(seen);
  return static_cast<int>(out->size());
}

int FindStreaks(const ImageView& image, const BackgroundModel& background, const BallColour& ball,
                double diameter_px, const StreakFinderOptions& finder_options,
                const StreakSearchOptions& search_options, StreakFinder* finder,
                StreakSearch* search, std::vector<FoundStreak>* out) {
  out->clear();
  if (!(diameter_px > 0.0)) return 0;
  std::vector<StreakCandidate> candidates;
  finder->Find(image, background, ball, finder_options, &candidates);
  StreakSearchOptions o = search_options;
  // The candidate's middle is a cell's centre: the streak's lies within a cell of it.
  o.search_px = std::min(o.search_px, 2.0 * finder_options.cell_blocks);
  for (const StreakCandidate& s : candidates) {
    if (s.length_px < 2.0 * diameter_px) continue;
    const auto hit = search->Find(image, background, ball, s.cx, s.cy, std::cos(s.angle),
                                  std::sin(s.angle), 1.5 * s.length_px, diameter_px, o);
    if (!hit) continue;
    out->push_back({*hit, diameter_px * std::sqrt(hit->share / hit->expected_share)});
  }
  return static_cast<int>(out->size());
}

}  // namespace p4::segment
