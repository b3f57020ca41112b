// The ball in another camera along a view's epipolar segment, by its edge (beyond the paper,
// whose epipolar search looks for the ball's colour regions near the line, §3.4).
//
// The colour tables know the ball's colour as it looked where they learnt it; at a dimmer end of
// the hall its shaded side, or all of it, may fall outside them, and a camera finds nothing while
// another sees the ball whole. That view fixes a ray, and its diameter the depth along it to
// some ten per cent: in the other camera the ball lies on a short segment of the epipolar line.
// Along it the ball's edge is fitted (segment/ball_edge.h) at the size the depth gives, every
// radius or so (where the ball merges on one side with something of its colour, its outline as a
// circle from single rays); a fit that holds there is the ball when it is round, of the expected
// size at the point the two views triangulate to, of the first view's hue (shading scales a
// colour's luma and chroma alike: the angle of (U, V) about grey stays), and the only one on the
// segment.
//
// Frames: pixels of each camera (distorted), points in the world frame, metres. Pure.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "p4/core/image.h"
#include "p4/geometry/camera.h"
#include "p4/segment/ball_edge.h"

namespace p4::track {

struct EpipolarSearchOptions {
  // The first view's depth (from its diameter) is searched from depth / ratio to depth * ratio.
  double depth_ratio = 1.4;
  // The fits are started this many expected radii apart along the segment (a fit converges from
  // about half a radius away).
  double step_radii = 0.8;
  int max_fits = 120;  // per segment: a segment longer than this many steps is searched coarser
  double epipolar_px = 4.0;  // the fit's centre from the epipolar line
  // The fit's diameter within this factor of the one expected at the triangulated point (no
  // colour table vouches for it: tighter than the tables' views).
  double max_size_ratio = 1.3;
  double max_elongation = 1.5;  // major / minor of the fit: a ball, not a streak (a line's rays)
  // Hue: both colours' chroma (distance of (U, V) from grey) at least min_chroma and their
  // angles about grey within max_hue_deg; a grey first view (a white ball) wants a grey one
  // (chroma below 2 min_chroma).
  double min_chroma = 8.0;
  double max_hue_deg = 30.0;
  // A grey first view (a white ball) is searched for only with this: grey is the colour of the
  // hall's lines, lamps and shirts, and a white ball merged with a shirt in the searched camera
  // leaves a round piece of the shirt alone on the segment (white tuning 6: false rows 0.6 ->
  // 2.6 %).
  bool grey_balls = false;
  // Where the ball can be: |x| and |y| at most these (m), the height between floor_z and
  // max_z (m, world frame).
  double half_length = 8.0, half_width = 6.0, floor_z = -0.78, max_z = 5.0;
  double ball_radius = 0.02;  // m
  // The fit: 60 % of the rays' pairs agreeing (a ball over a table's line loses a third of its
  // rays to it; the tables' views are fitted with 75 %, but there a colour region vouches).
  segment::EdgeCentreOptions edge = [] {
    segment::EdgeCentreOptions e;
    e.min_pair_share = 0.6;
    return e;
  }();
  // Where that fit fails and the ball there is expected this wide or more (px), its outline is
  // fitted as a circle from single rays (segment::MeasureEdgeCircle): the ball merged on one
  // side with a hand or a shirt of its colour, or half hidden, whose rays there find no edge
  // (sports tuning 34: a toss rising against the server's ball-coloured sleeve, its outline
  // plain on 200 degrees). Smaller balls are left to the pair fit: a few pixels' arc fixes no
  // centre (with no floor, webcam tuning 3 took false circles: 9.0 -> 120 mm). 0: off. Only for
  // a first view of this chroma or more: the circle is judged by its hue alone, which says
  // little near grey (a white ball under warm light, 11 from grey, found round pieces of white
  // shirts and lines: white tuning 3 4.28 -> 6.87 mm, 0.79 % false rows).
  double circle_min_diameter_px = 8.0;
  double circle_min_chroma = 24.0;
  segment::EdgeCircleOptions circle;

  bool IsValid(std::string* error) const;
};

struct EpipolarFind {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // the ball's centre in the searched camera
  double diameter_px = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // the two views triangulated (world, m)
  double size_misfit = 0.0;                         // |log(measured / expected diameter)|
  int fits = 0;                                     // edge fits tried
};

// The ball of camera `a`'s view (centre `pixel_a`, diameter `diameter_a` px, its colour
// `colour_a` Y, U, V as the edge fit measured it) in camera `b`'s image: the best fit along the
// segment (least size misfit), or nullopt, also when two fits a diameter or more apart pass
// (the view cannot tell which is the ball). Preconditions: options valid, diameter_a > 0, the
// image camera b's.
std::optional<EpipolarFind> SearchAlongEpipolar(const Camera& a, const Eigen::Vector2d& pixel_a,
                                                double diameter_a, const double colour_a[3],
                                                const Camera& b, const ImageView& image_b,
                                                const EpipolarSearchOptions& options = {});

// Whether two colours (Y, U, V) share a hue as EpipolarSearchOptions says.
bool SameHue(const double colour_a[3], const double colour_b[3], double min_chroma,
             double max_hue_deg);

}  // namespace p4::track
