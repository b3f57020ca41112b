#include "p4/segment/background_model.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "p4/core/robust.h"
#include "p4/segment/pixel_access.h"

namespace p4::segment {
namespace {

using internal::LumaAt;

// A block's chroma pair (YUYV: its top row's).
inline void ChromaOf(const ImageView& image, int bx, int by, float* u, float* v) {
  uint8_t cu = 128, cv = 128;
  internal::ChromaAt(image, 2 * bx, 2 * by, &cu, &cv);
  *u = cu, *v = cv;
}

// A block's model moved towards what is seen at `rate`: its four pixels' luma, its chroma by
// (du, dv) (what is seen minus the model) and its noise sigmas (mean absolute deviation x 1.25 ~
// sigma, for a Gaussian), not below their floors. The short-term and the long-term model learn
// alike.
inline void LearnBlock(float* const model[4], const float seen[4], float dy, float du, float dv,
                       float rate, float floor_y, float floor_c, float* u, float* v, float* sy,
                       float* sc) {
  for (int k = 0; k < 4; ++k) *model[k] += rate * (seen[k] - *model[k]);
  *u += rate * du;
  *v += rate * dv;
  *sy = std::max(floor_y, *sy + rate * (1.25f * std::abs(dy) - *sy));
  *sc = std::max(floor_c, *sc + rate * (0.9f * (std::abs(du) + std::abs(dv)) - *sc));
}

// The block's mean luma.
inline float MeanOf(float* const model[4]) {
  return 0.25f * (*model[0] + *model[1] + *model[2] + *model[3]);
}

}  // namespace

bool BackgroundOptions::IsValid(std::string* error) const {
  if (!(learn_rate > 0.0 && learn_rate <= 1.0) ||
      !(held_learn_rate >= 0.0 && held_learn_rate <= learn_rate) ||
      !(still_learn_rate >= held_learn_rate && still_learn_rate <= learn_rate) ||
      settle_frames < 1) {
    if (error) {
      *error =
          "background: need 0 < learn rate <= 1, 0 <= held rate <= still rate <= learn rate and "
          "a settling of >= 1 frame";
    }
    return false;
  }
  if (row_stride < 1 || row_stride > 16 || warmup_frames < 1) {
    if (error) *error = "background: row stride must be 1-16 and warm-up >= 1 frame";
    return false;
  }
  if (!(min_sigma_luma > 0.0 && min_sigma_chroma > 0.0 && foreground_sigmas > 0.0)) {
    if (error) *error = "background: noise floors and the foreground bound must be positive";
    return false;
  }
  return true;
}

BackgroundModel::BackgroundModel(int width, int height, const BackgroundOptions& options)
    : options_(options), width_(width & ~1), height_(height & ~1), bw_(width / 2), bh_(height / 2) {
  y_.assign(static_cast<std::size_t>(width_) * height_, 16.0f);
  u_.assign(static_cast<std::size_t>(bw_) * bh_, 128.0f);
  v_.assign(u_.size(), 128.0f);
  by_.assign(u_.size(), 16.0f);
  last_.assign(u_.size(), Yuv{});
  sy_.assign(u_.size(), static_cast<float>(1.5 * options.min_sigma_luma));
  sc_.assign(u_.size(), static_cast<float>(1.5 * options.min_sigma_chroma));
  iy_.assign(u_.size(), 1.0f / (sy_[0] * sy_[0]));
  ic_.assign(u_.size(), 1.0f / (sc_[0] * sc_[0]));
  if (options.long_term) {
    ly_ = y_, lu_ = u_, lv_ = v_, lby_ = by_, lsy_ = sy_, lsc_ = sc_;
    settling_.assign(u_.size(), 0);
  }
}

Yuv BackgroundModel::BlockOfAnyFormat(const ImageView& image, int bx, int by) {
  Yuv c;
  c.y = 0.25f * (LumaAt(image, 2 * bx, 2 * by) + LumaAt(image, 2 * bx + 1, 2 * by) +
                 LumaAt(image, 2 * bx, 2 * by + 1) + LumaAt(image, 2 * bx + 1, 2 * by + 1));
  ChromaOf(image, bx, by, &c.u, &c.v);
  return c;
}

void BackgroundModel::EstimateGain(const ImageView& image) {
  // The median ratio of the picture's levels above black to the model's, over a sparse grid of
  // blocks that are neither dark nor clipped: the exposure, whatever moves in front of it.
  ratios_.clear();
  for (int by = 3; by < bh_; by += 8) {
    for (int bx = 3; bx < bw_; bx += 8) {
      const std::size_t p = static_cast<std::size_t>(2 * by) * width_ + 2 * bx;
      const float model = y_[p] - 16.0f;
      const float seen = LumaAt(image, 2 * bx, 2 * by) - 16.0f;
      if (model > 30.0f && seen > 4.0f && seen < 225.0f) ratios_.push_back(seen / model);
    }
  }
  if (ratios_.size() < 16) {
    gain_ = 1.0;
  } else {
    gain_ = std::clamp(static_cast<double>(MedianInPlace(ratios_)), 0.25, 4.0);
  }
  gain_f_ = static_cast<float>(gain_);
}

void BackgroundModel::Update(const ImageView& image, const Roi& keep) {
  if (frames_ == 0) {
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x)
        y_[static_cast<std::size_t>(y) * width_ + x] = LumaAt(image, x, y);
    }
    for (int by = 0; by < bh_; ++by) {
      for (int bx = 0; bx < bw_; ++bx) {
        const std::size_t b = Index(bx, by);
        ChromaOf(image, bx, by, &u_[b], &v_[b]);
        const std::size_t p = static_cast<std::size_t>(2 * by) * width_ + 2 * bx;
        by_[b] = 0.25f * (y_[p] + y_[p + 1] + y_[p + width_] + y_[p + width_ + 1]);
        last_[b] = {by_[b], u_[b], v_[b]};
      }
    }
    if (options_.long_term) {
      ly_ = y_, lu_ = u_, lv_ = v_, lby_ = by_;
    }
    ++frames_;
    return;
  }
  EstimateGain(image);
  const float inv = 1.0f / gain_f_;
  const float k2 = static_cast<float>(options_.foreground_sigmas * options_.foreground_sigmas);
  // A block row is visited every row_stride frames: the rates of that many frames at once.
  const auto learn =
      static_cast<float>(1.0 - std::pow(1.0 - options_.learn_rate, options_.row_stride));
  const auto held =
      static_cast<float>(1.0 - std::pow(1.0 - options_.held_learn_rate, options_.row_stride));
  const auto still =
      static_cast<float>(1.0 - std::pow(1.0 - options_.still_learn_rate, options_.row_stride));
  // The long-term model learns on every kLongPasses-th pass over the rows (it need not follow
  // faster), at the rate of that many frames.
  const bool long_pass = options_.long_term && passes_ % kLongPasses == 0;
  const int long_frames = options_.row_stride * kLongPasses;
  const auto long_learn =
      static_cast<float>(1.0 - std::pow(1.0 - options_.learn_rate, long_frames));
  const auto settle_visits =
      static_cast<uint32_t>((options_.settle_frames + long_frames - 1) / long_frames);
  const auto floor_y = static_cast<float>(options_.min_sigma_luma);
  const auto floor_c = static_cast<float>(options_.min_sigma_chroma);
  const bool packed = image.format == PixelFormat::kYUYV;
  // The rows, with the long-term model's work compiled in or out (without it, the loop is the
  // short-term model's alone, at its own speed).
  const auto rows = [&](auto with_long_term) {
    constexpr bool kLongTerm = decltype(with_long_term)::value;
    for (int by = next_row_; by < bh_; by += options_.row_stride) {
      const uint8_t* top = packed ? nullptr : image.planes[0].Row(2 * by);
      const uint8_t* bottom = packed ? nullptr : image.planes[0].Row(2 * by + 1);
      for (int bx = 0; bx < bw_; ++bx) {
        const std::size_t b = Index(bx, by);
        const std::size_t p = static_cast<std::size_t>(2 * by) * width_ + 2 * bx;
        // The frame brought to the model's exposure.
        float seen[4];
        if (packed) {
          seen[0] = LumaAt(image, 2 * bx, 2 * by), seen[1] = LumaAt(image, 2 * bx + 1, 2 * by);
          seen[2] = LumaAt(image, 2 * bx, 2 * by + 1);
          seen[3] = LumaAt(image, 2 * bx + 1, 2 * by + 1);
        } else {
          seen[0] = top[2 * bx], seen[1] = top[2 * bx + 1];
          seen[2] = bottom[2 * bx], seen[3] = bottom[2 * bx + 1];
        }
        for (float& x : seen) x = 16.0f + inv * (x - 16.0f);
        float u = 128.0f, v = 128.0f;
        ChromaOf(image, bx, by, &u, &v);
        u = 128.0f + inv * (u - 128.0f);
        v = 128.0f + inv * (v - 128.0f);
        float* model[4] = {&y_[p], &y_[p + 1], &y_[p + width_], &y_[p + width_ + 1]};
        float dy = 0.25f * (seen[0] + seen[1] + seen[2] + seen[3] -
                            (*model[0] + *model[1] + *model[2] + *model[3]));
        float du = u - u_[b], dv = v - v_[b];
        bool differs = dy * dy * iy_[b] + (du * du + dv * dv) * ic_[b] > k2;
        const bool like_short = !differs;
        const float mean_seen = 0.25f * (seen[0] + seen[1] + seen[2] + seen[3]);
        // The long-term model's distance, in its own noise (only where it matters: a block that
        // differs, and the long-term model's own passes).
        float ldy = 0.0f, ldu = 0.0f, ldv = 0.0f;
        bool like_long = false;
        if (kLongTerm && (differs || long_pass)) {
          ldy = mean_seen - lby_[b], ldu = u - lu_[b], ldv = v - lv_[b];
          const float ily = 1.0f / (lsy_[b] * lsy_[b]), ilc = 1.0f / (lsc_[b] * lsc_[b]);
          like_long = ldy * ldy * ily + (ldu * ldu + ldv * ldv) * ilc <= k2;
          // The short-term model away from the long-term one (its own noise has grown while it
          // learnt what came to rest, so the long-term one's).
          const float sly = by_[b] - lby_[b], slu = u_[b] - lu_[b], slv = v_[b] - lv_[b];
          const bool apart = sly * sly * ily + (slu * slu + slv * slv) * ilc > k2;
          if (differs && apart) {
            // What the short-term model learnt of something that rested is no longer there (the
            // hall behind a player who stepped away, or something before it): the long-term
            // model back.
            for (int k = 0; k < 4; ++k) *model[k] = ly_[p + (k & 1) + (k >> 1) * width_];
            u_[b] = lu_[b], v_[b] = lv_[b], sy_[b] = lsy_[b], sc_[b] = lsc_[b];
            iy_[b] = ily, ic_[b] = ilc;
            dy = ldy, du = ldu, dv = ldv;
            differs = !like_long;
          }
        }
        if (kLongTerm && long_pass) {
          // The long-term model learns where the frame looks like it; what looked like the
          // short-term model only (came to rest) for settle_frames becomes it.
          float* long_model[4] = {&ly_[p], &ly_[p + 1], &ly_[p + width_], &ly_[p + width_ + 1]};
          if (like_long) {
            settling_[b] = 0;
            LearnBlock(long_model, seen, ldy, ldu, ldv, long_learn, floor_y, floor_c, &lu_[b],
                       &lv_[b], &lsy_[b], &lsc_[b]);
          } else if (like_short && ++settling_[b] >= settle_visits) {
            settling_[b] = 0;
            for (int k = 0; k < 4; ++k) *long_model[k] = *model[k];
            lu_[b] = u_[b], lv_[b] = v_[b], lsy_[b] = sy_[b], lsc_[b] = sc_[b];
          }
          lby_[b] = MeanOf(long_model);
        }
        // Unchanged since the last visit (within the noise)?
        const Yuv& last = last_[b];
        const float cy = mean_seen - last.y, cu = u - last.u, cv = v - last.v;
        const bool unchanged = cy * cy * iy_[b] + (cu * cu + cv * cv) * ic_[b] < k2;
        last_[b] = {mean_seen, u, v};
        const bool kept = !keep.empty() && 2 * bx + 1 >= keep.x0 && 2 * bx < keep.x1 &&
                          2 * by + 1 >= keep.y0 && 2 * by < keep.y1;
        const float rate = kept && differs ? held : (!differs ? learn : (unchanged ? still : held));
        // (Slowly where something differs, so that a noisier block than the model thought is
        // learnt in the end.)
        LearnBlock(model, seen, dy, du, dv, rate, floor_y, floor_c, &u_[b], &v_[b], &sy_[b],
                   &sc_[b]);
        by_[b] = MeanOf(model);
        iy_[b] = 1.0f / (sy_[b] * sy_[b]);
        ic_[b] = 1.0f / (sc_[b] * sc_[b]);
      }
    }
  };
  if (options_.long_term) {
    rows(std::true_type{});
  } else {
    rows(std::false_type{});
  }
  next_row_ = (next_row_ + 1) % options_.row_stride;
  if (next_row_ == 0) ++passes_;
  ++frames_;
}

}  // namespace p4::segment
