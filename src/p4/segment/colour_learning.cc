#include "p4/segment/colour_learning.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "p4/core/robust.h"
#include "p4/segment/pixel_access.h"

namespace p4::segment {

ColorClassSet AnyColour() {
  ColorClassSet set;
  set.classes.push_back({"ball_any", {0, 255}, {0, 255}, {0, 255}});
  return set;
}

bool ColourLearningOptions::IsValid(std::string* error) const {
  if (!(core_share > 0.0 && core_share <= 1.0) || !(min_sigmas >= 0.0) || min_samples < 1 ||
      boxes < 1 || boxes > 8 || margin < 0 || margin > 64 ||
      !(max_ball_loss >= 0.0 && max_ball_loss < 1.0) || !(moving_over_ball > 0.0) ||
      moving_stride < 1) {
    if (error) {
      *error =
          "colour learning: core share in (0, 1], samples >= 1, 1-8 boxes, margin 0-64, "
          "ball loss in [0, 1), a positive moving-over-ball ratio, moving stride >= 1";
    }
    return false;
  }
  return true;
}

void ColourSamples::AddDisc(const ImageView& image, const Eigen::Vector2d& centre,
                            double diameter_px, const ColourLearningOptions& options,
                            const BackgroundModel* background) {
  const double r = 0.5 * diameter_px * options.core_share;
  if (!(r > 0.0)) return;
  ball_weight_ = 1.0 / (options.core_share * options.core_share);
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

void ColourSamples::AddMoving(const ImageView& image, const BackgroundModel& background,
                              std::span<const Eigen::Vector2d> balls, double clear_px,
                              const ColourLearningOptions& options) {
  if (!background.ready() || background.width() != (image.width & ~1) ||
      background.height() != (image.height & ~1)) {
    return;
  }
  const int stride = options.moving_stride;
  moving_weight_ = static_cast<double>(stride) * stride;
  const double k2 = options.min_sigmas * options.min_sigmas;
  for (int y = 0; y < background.height(); y += stride) {
    for (int x = 0; x < background.width(); x += stride) {
      if (background.BlockDistance2(image, x / 2, y / 2) <= k2) continue;
      const Eigen::Vector2d p(x, y);
      if (std::any_of(balls.begin(), balls.end(),
                      [&](const Eigen::Vector2d& b) { return (b - p).norm() < clear_px; })) {
        continue;
      }
      YuvSample s{internal::LumaAt(image, x, y), 0, 0};
      internal::ChromaAt(image, x, y, &s.u, &s.v);
      moving_.push_back(s);
    }
  }
}

double TakenShare(std::span<const ColorClass> boxes, std::span<const YuvSample> samples) {
  if (samples.empty()) return 0.0;
  const auto taken = std::count_if(samples.begin(), samples.end(), [&](const YuvSample& s) {
    return std::any_of(boxes.begin(), boxes.end(),
                       [&](const ColorClass& b) { return b.Contains(s.y, s.u, s.v); });
  });
  return static_cast<double>(taken) / static_cast<double>(samples.size());
}

void ColourSamples::GiveUpMovingColours(const ColourLearningOptions& options,
                                        LearnedColour* out) const {
  // Colours in cells of 4 levels a channel, each with the pixels of the pictures it stands for:
  // the ball's and the moving hall's.
  constexpr int kShift = 2, kCells = 256 >> kShift;
  struct Cell {
    std::array<int, 3> c;
    double ball = 0.0, moving = 0.0;
  };
  std::vector<int> index(static_cast<std::size_t>(kCells) * kCells * kCells, -1);
  std::vector<Cell> cells;
  const auto add = [&](const YuvSample& s, double Cell::*field, double weight) {
    const std::array<int, 3> c = {s.y >> kShift, s.u >> kShift, s.v >> kShift};
    int& i = index[(static_cast<std::size_t>(c[0]) * kCells + c[1]) * kCells + c[2]];
    if (i < 0) i = static_cast<int>(cells.size()), cells.push_back({c});
    cells[static_cast<std::size_t>(i)].*field += weight;
  };
  double ball_total = 0.0;
  for (const YuvSample& s : samples_) add(s, &Cell::ball, ball_weight_), ball_total += ball_weight_;
  for (const YuvSample& s : moving_) add(s, &Cell::moving, moving_weight_);
  // The boxes in cells: lo[axis], hi[axis] inclusive.
  struct Box {
    std::array<int, 3> lo, hi;
    std::array<bool, 6> cut{};  // which faces moved (lo y, hi y, lo u, ...)
  };
  std::vector<Box> boxes;
  for (const ColorClass& k : out->classes.classes) {
    boxes.push_back({{k.y[0] >> kShift, k.u[0] >> kShift, k.v[0] >> kShift},
                     {k.y[1] >> kShift, k.u[1] >> kShift, k.v[1] >> kShift}});
  }
  const auto in = [](const Box& b, const Cell& cell) {
    for (int a = 0; a < 3; ++a) {
      if (cell.c[a] < b.lo[a] || cell.c[a] > b.hi[a]) return false;
    }
    return true;
  };
  // Greedy: of every face of every box, the slab of any depth (the colours to give up may lie
  // inside the box, behind layers that hold nothing) whose cut gives up the most moving pixels
  // beyond moving_over_ball times the ball's, within the budget of the ball's pixels.
  double lost = 0.0;
  std::vector<double> layer_ball, layer_moving;
  for (;;) {
    double best_gain = 0.0, best_ball = 0.0;
    int best_box = -1, best_face = -1, best_depth = 0;
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      for (int face = 0; face < 6; ++face) {
        const int axis = face / 2;
        const bool low = face % 2 == 0;
        const int thickness = boxes[b].hi[axis] - boxes[b].lo[axis] + 1;
        if (thickness < 2) continue;  // one cell thick: it stays
        // The pixels that leave the box with each layer (a colour the bands share leaves the
        // classes when every box that takes it has given it up: the budget counts it each time).
        layer_ball.assign(static_cast<std::size_t>(thickness), 0.0);
        layer_moving.assign(layer_ball.size(), 0.0);
        for (const Cell& cell : cells) {
          if (!in(boxes[b], cell)) continue;
          const auto depth = static_cast<std::size_t>(low ? cell.c[axis] - boxes[b].lo[axis]
                                                          : boxes[b].hi[axis] - cell.c[axis]);
          layer_ball[depth] += cell.ball, layer_moving[depth] += cell.moving;
        }
        double ball = 0.0, moving = 0.0;
        for (int depth = 1; depth < thickness; ++depth) {  // at least one layer stays
          ball += layer_ball[static_cast<std::size_t>(depth - 1)];
          moving += layer_moving[static_cast<std::size_t>(depth - 1)];
          if (lost + ball > options.max_ball_loss * ball_total) break;
          if (moving - options.moving_over_ball * ball > best_gain) {
            best_gain = moving - options.moving_over_ball * ball, best_ball = ball;
            best_box = static_cast<int>(b), best_face = face, best_depth = depth;
          }
        }
      }
    }
    if (best_box < 0) break;
    Box& box = boxes[static_cast<std::size_t>(best_box)];
    const int axis = best_face / 2;
    if (best_face % 2 == 0) {
      box.lo[axis] += best_depth;
    } else {
      box.hi[axis] -= best_depth;
    }
    box.cut[static_cast<std::size_t>(best_face)] = true;
    lost += best_ball;
  }
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    ColorClass& k = out->classes.classes[b];
    std::array<std::array<uint8_t, 2>*, 3> range = {&k.y, &k.u, &k.v};
    for (int a = 0; a < 3; ++a) {
      if (boxes[b].cut[2 * a]) (*range[a])[0] = static_cast<uint8_t>(boxes[b].lo[a] << kShift);
      if (boxes[b].cut[2 * a + 1]) {
        (*range[a])[1] = static_cast<uint8_t>((boxes[b].hi[a] << kShift) + (1 << kShift) - 1);
      }
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
  const Yuv lit{MedianInPlace(ys), MedianInPlace(us), MedianInPlace(vs)};
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
  const float med = Median(off);
  std::vector<float> dev = off;
  // (At most max_off_line: a spread wider than that is a mixture, the ball and something else.)
  const double bound =
      std::clamp(med + 3.0 * RobustSigmaInPlace(dev, med), 4.0, options.max_off_line);
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
  if (!moving_.empty()) {
    const double ball_before = TakenShare(out->classes.classes, samples_);
    out->moving_taken_before = TakenShare(out->classes.classes, moving_);
    GiveUpMovingColours(options, out);
    out->moving_taken = TakenShare(out->classes.classes, moving_);
    out->ball_lost = ball_before - TakenShare(out->classes.classes, samples_);
  }
  return true;
}

}  // namespace p4::segment
