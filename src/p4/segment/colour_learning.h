// The ball's colour learned from the scene (beyond the paper, whose §3.1 boxes are set by hand
// for one hall): pixels of the ball's core, where a tracker that needs no colour found it flying
// (pipeline/learn_colour.h), are filled into the paper's colour classes (three look-up tables
// of 32-bit masks), and the ball's lit colour into a BallColour for the background detector.
//
// Pixel coordinates: centres at integers. YUV as the camera delivers it (8-bit). Pure.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/color_classes.h"

namespace p4::segment {

// One class that takes every colour: with a background mask, "whatever moves" (the learner's
// detector before it knows the ball's colour).
ColorClassSet AnyColour();

struct ColourLearningOptions {
  double core_share = 0.35;    // pixels within this share of the ball's radius are sampled...
  double min_sigmas = 4.0;     // ...where their block differs from the background by this much
  int min_samples = 200;       // fewer pixels than this learn nothing
  int boxes = 3;               // bands of shade along the ball's shading line
  int margin = 8;              // levels added around each box
  double max_off_line = 12.0;  // chroma levels a sample of the ball may lie off its shading line
  // The boxes give up colours that the hall's moving pixels (arms, heads, shirts; added with
  // AddMoving) have more of than the ball: a slab (4-level layers at a face of a box) is cut
  // when the moving pixels it takes outnumber moving_over_ball times the ball's (both counted
  // per pixel of the pictures), while at most max_ball_loss of the ball's pixels are lost.
  double moving_over_ball = 16.0;  // chosen on sports tuning scenes 1-32 (docs/DECISIONS.md)
  double max_ball_loss = 0.2;
  int moving_stride = 4;  // AddMoving samples every n-th pixel across and down

  bool IsValid(std::string* error) const;
};

struct LearnedColour {
  ColorClassSet classes;  // "ball_0".., one box per band of shade along the shading line
  BallColour ball;        // lit: the median of the brightest third of the samples
  int samples = 0;        // samples on the line that the boxes were drawn from
  // Of the moving pixels that are not the ball, the share the boxes took before and after they
  // gave up colours; the share of the ball's pixels given up.
  double moving_taken_before = 0.0;
  double moving_taken = 0.0;
  double ball_lost = 0.0;
};

// The share of `samples` that any of `boxes` takes (0 without samples).
double TakenShare(std::span<const ColorClass> boxes, std::span<const YuvSample> samples);

class ColourSamples {
 public:
  // Samples the core of a ball seen at `centre` with `diameter_px` (pixels inside the image):
  // with a ready background model of the image's size, only pixels that differ from it (a
  // small or blurred ball's core still shows the hall behind it).
  void AddDisc(const ImageView& image, const Eigen::Vector2d& centre, double diameter_px,
               const ColourLearningOptions& options = {},
               const BackgroundModel* background = nullptr);
  // Samples what moves in the picture and is not the ball: every options.moving_stride-th pixel
  // whose block differs from the (ready) background by min_sigmas, farther than `clear_px` from
  // every one of `balls` (the ball's views in this picture; its blur and shadow stay out).
  void AddMoving(const ImageView& image, const BackgroundModel& background,
                 std::span<const Eigen::Vector2d> balls, double clear_px,
                 const ColourLearningOptions& options = {});
  int size() const { return static_cast<int>(samples_.size()); }
  int moving() const { return static_cast<int>(moving_.size()); }
  const std::vector<YuvSample>& samples() const { return samples_; }

  // False (and *error says why) with too few samples.
  bool Learn(const ColourLearningOptions& options, LearnedColour* out, std::string* error) const;

 private:
  // Cuts slabs off the boxes where the moving pixels outnumber the ball's (max_ball_loss).
  void GiveUpMovingColours(const ColourLearningOptions& options, LearnedColour* out) const;

  std::vector<YuvSample> samples_;
  std::vector<YuvSample> moving_;
  double ball_weight_ = 1.0;    // pixels of the picture each ball sample stands for
  double moving_weight_ = 1.0;  // ...and each moving sample
};

}  // namespace p4::segment
