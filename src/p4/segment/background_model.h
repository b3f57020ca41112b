// What a still camera sees without the ball (beyond the paper): per pixel its luma, per 2x2
// block (the chroma's own resolution) its chroma and how much the block varies from frame to
// frame (sensor noise, the encoder, flicker). Lamps, lines, banners, logos and a ball lying on
// the floor become background; the ball in flight, players and their arms do not.
//
// Learning: a block that looks like the background learns at `learn_rate` per frame, one that
// differs from it at `held_learn_rate` (so a ball held still for a serve's toss fades in over
// seconds, not frames), one that differs but stays as it was at `still_learn_rate` (a bag put
// down). Updates visit every `row_stride`-th block row per frame, in turn, so the model costs a
// fraction of a full pass a frame. The camera's exposure (auto-exposure drift, flicker) is
// followed by a per-frame gain estimated from the whole picture, applied to the model before any
// comparison.
//
// Two models: the short-term one above, which detection compares with, and a long-term one that
// learns only where the frame looks like it (and takes what came to rest when it has stayed for
// `settle_frames`). A player who stood still for a serve is learnt by the short-term model
// within a second; when they step away, the hall behind them differs from it (a "ghost" the size
// of a torso, which a ball before it joins and is lost in) but looks like the long-term model:
// such a block takes the long-term model back at once (at its next visit).
//
// Pixel coordinates as everywhere (centres at integers); block (bx, by) covers pixels
// 2bx..2bx+1, 2by..2by+1. Pure: the caller hands in each frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/blob_finder.h"

namespace p4::segment {

struct BackgroundOptions {
  double learn_rate = 0.02;         // per frame, blocks that look like background
  double held_learn_rate = 0.0005;  // per frame, blocks that differ and change (the ball, players)
  // Per frame, blocks that differ but stay as they were since the last visit: something that
  // came to rest (a bag put down, a player who walked away) becomes background in seconds.
  double still_learn_rate = 0.01;
  // The long-term model (see above); off, the short-term model alone. On only where the
  // background is the detector (track_command.cc: a white ball, --detector background); the
  // colour tables' helpers, the colour learner, the offset search and the findable ceiling keep
  // the short-term model their thresholds were chosen with (docs/DECISIONS.md, "Detection").
  bool long_term = false;
  // Frames a block must look like the short-term model and not the long-term one (something
  // that came to rest and stayed) before the long-term model takes it as the hall.
  int settle_frames = 600;
  int row_stride = 8;           // block rows updated per frame: every row_stride-th
  double min_sigma_luma = 2.0;  // floors of a block's noise, 8-bit levels
  double min_sigma_chroma = 1.5;
  double foreground_sigmas = 4.0;  // a block differs when its distance exceeds this many sigmas
  int warmup_frames = 6;           // frames before the model is used

  bool IsValid(std::string* error) const;
};

class BackgroundModel {
 public:
  BackgroundModel() = default;
  BackgroundModel(int width, int height, const BackgroundOptions& options);

  // Learns from a frame (the first one initialises the model). Blocks inside `keep` (the
  // tracker's window around the ball it follows) learn at the held rate whatever they show, so a
  // ball that rests in a hand is not learnt. Precondition: the image has the model's size.
  void Update(const ImageView& image, const Roi& keep = {});

  bool ready() const { return frames_ >= options_.warmup_frames; }
  int width() const { return width_; }
  int height() const { return height_; }
  double gain() const { return gain_; }  // this frame's exposure relative to the model's
  const BackgroundOptions& options() const { return options_; }

  // The background at a pixel and at a block, in this frame's exposure.
  float Luma(int x, int y) const {
    return 16.0f + gain_f_ * (y_[static_cast<std::size_t>(y) * width_ + x] - 16.0f);
  }
  Yuv Block(int bx, int by) const {
    const std::size_t b = Index(bx, by);
    return {16.0f + gain_f_ * (by_[b] - 16.0f), 128.0f + gain_f_ * (u_[b] - 128.0f),
            128.0f + gain_f_ * (v_[b] - 128.0f)};
  }
  // Noise of a block's luma mean and of its chroma (sigmas, levels).
  float SigmaLuma(int bx, int by) const { return sy_[Index(bx, by)]; }
  float SigmaChroma(int bx, int by) const { return sc_[Index(bx, by)]; }

  // The block's mean colour in `image` (luma averaged over its 4 pixels).
  static Yuv BlockOf(const ImageView& image, int bx, int by) {
    if (image.format != PixelFormat::kI420) return BlockOfAnyFormat(image, bx, by);
    const uint8_t* top = image.planes[0].Row(2 * by) + 2 * bx;
    const uint8_t* bottom = image.planes[0].Row(2 * by + 1) + 2 * bx;
    return {0.25f * static_cast<float>(top[0] + top[1] + bottom[0] + bottom[1]),
            static_cast<float>(image.planes[1].Row(by)[bx]),
            static_cast<float>(image.planes[2].Row(by)[bx])};
  }
  static Yuv BlockOfAnyFormat(const ImageView& image, int bx, int by);
  // Squared distance of the block in `image` from the background, in sigmas.
  double BlockDistance2(const ImageView& image, int bx, int by) const {
    return Distance2(BlockOf(image, bx, by), Block(bx, by), bx, by);
  }
  // The same for a block's colour `seen` against the background's `model` (Block()).
  double Distance2(const Yuv& seen, const Yuv& model, int bx, int by) const {
    const std::size_t b = Index(bx, by);
    const float dy = seen.y - model.y, du = seen.u - model.u, dv = seen.v - model.v;
    return dy * dy * iy_[b] + (du * du + dv * dv) * ic_[b];
  }

 private:
  std::size_t Index(int bx, int by) const {
    return static_cast<std::size_t>(by) * bw_ + static_cast<std::size_t>(bx);
  }
  void EstimateGain(const ImageView& image);

  BackgroundOptions options_;
  int width_ = 0, height_ = 0, bw_ = 0, bh_ = 0;
  std::vector<float> y_;        // per pixel, at exposure 1
  std::vector<float> u_, v_;    // per block, at exposure 1
  std::vector<float> by_;       // per block: mean luma at exposure 1
  std::vector<float> sy_, sc_;  // per block: noise sigmas
  std::vector<float> iy_, ic_;  // per block: 1 / sigma^2
  std::vector<Yuv> last_;       // per block: what the last visit saw (exposure 1)
  // The long-term model (empty without long_term): per pixel luma, per block chroma and noise
  // sigmas (exposure 1).
  std::vector<float> ly_, lu_, lv_, lsy_, lsc_, lby_;  // lby_: per block mean luma
  std::vector<uint32_t> settling_;  // per block: visits like the short-term model only
  int frames_ = 0;
  int next_row_ = 0;
  int passes_ = 0;                       // passes over every block row
  static constexpr int kLongPasses = 4;  // the long-term model learns on every 4th
  double gain_ = 1.0;
  float gain_f_ = 1.0f;
  std::vector<float> ratios_;  // gain estimation scratch
};

}  // namespace p4::segment
