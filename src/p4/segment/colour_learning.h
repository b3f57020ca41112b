// The ball's colour learned from the scene (beyond the paper, whose §3.1 boxes are set by hand
// for one hall): pixels of the ball's core, where a tracker that needs no colour found it flying
// (pipeline/learn_colour.h), are filled into the paper's colour classes (three look-up tables
// of 32-bit masks), and the ball's lit colour into a BallColour for the background detector.
//
// Pixel coordinates: centres at integers. YUV as the camera delivers it (8-bit). Pure.
#pragma once

#include <Eigen/Core>
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

  bool IsValid(std::string* error) const;
};

struct LearnedColour {
  ColorClassSet classes;  // "ball_0".., one box per band of shade along the shading line
  BallColour ball;        // lit: the median of the brightest third of the samples
  int samples = 0;        // samples on the line that the boxes were drawn from
};

class ColourSamples {
 public:
  // Samples the core of a ball seen at `centre` with `diameter_px` (pixels inside the image):
  // with a ready background model of the image's size, only pixels that differ from it (a
  // small or blurred ball's core still shows the hall behind it).
  void AddDisc(const ImageView& image, const Eigen::Vector2d& centre, double diameter_px,
               const ColourLearningOptions& options = {},
               const BackgroundModel* background = nullptr);
  int size() const { return static_cast<int>(samples_.size()); }
  const std::vector<YuvSample>& samples() const { return samples_; }

  // False (and *error says why) with too few samples.
  bool Learn(const ColourLearningOptions& options, LearnedColour* out, std::string* error) const;

 private:
  std::vector<YuvSample> samples_;
};

}  // namespace p4::segment
