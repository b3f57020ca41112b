// `--ball auto`: the ball's colour learned from the first seconds of the sources (beyond the
// paper's hand-set boxes, §3.1). A tracker that needs no colour looks at what differs from each
// camera's background (any colour), keeps what is the ball's size in every view and agrees across
// views (epipolar, §3.4), and starts a track only on what flies (track::TrackInitiator); the
// core pixels of every view the filter then takes over the table (where the ball in play flies
// and players' shoes and bodies are not) are the ball's colour samples, filled into the paper's
// colour classes (segment/colour_learning.h). The edge: reads the sources.
#pragma once

#include <string>
#include <vector>

#include "p4/geometry/rig.h"
#include "p4/segment/colour_learning.h"
#include "p4/track/frame_set_tracker.h"

namespace p4 {

struct LearnColourOptions {
  double max_seconds = 10.0;  // of the sources looked at, at most
  // It stops early after min_views views of the ball taken by the filter, in min_tracks tracks
  // (one flight could be a shoe), with twice the pixels the learning needs.
  int min_views = 60;
  int min_tracks = 2;
  int candidates_per_camera = 24;  // whatever moves is a candidate, the ball among many
  double max_height = 1.0;   // m above the table top: views over the table below it are sampled
  double min_speed = 1.5;    // m/s: ...while the track flies at least this fast
  double mask_sigmas = 5.0;  // what differs from the hall by this many sigmas (less: noise)
  // What moves in a sampled picture farther than this many ball diameters from the ball is not
  // the ball (segment::ColourSamples::AddMoving): the colours give up what it has more of.
  double moving_clear = 2.0;
  segment::ColourLearningOptions learning;
  track::FrameSetOptions tracking;  // its classes are AnyColour(), its detector masked
  // One camera (LearnNamedColour): the named classes stay when they take at least this share of
  // the ball's sampled pixels; the learnt ones replace them where they miss more (a dim hall's
  // shaded ball, of which they took the lit cap; an orange ball's shade over a red-brown floor).
  // Chosen on mono tuning scenes 1-24: the named classes take 91-100 % there, or 1-45 %.
  double keep_named_share = 0.75;

  bool IsValid(std::string* error) const;
};

struct LearnColourResult {
  segment::LearnedColour colour;
  int views = 0;         // ball views sampled
  int tracks = 0;        // tracks they came from
  double seconds = 0.0;  // of the sources looked at
  // LearnNamedColour: the share of the ball's sampled pixels its named classes take.
  double named_taken = 0.0;
};

// Throws p4::Error when the ball was not seen flying enough to learn its colour, or what flew has
// no ball's colour (a dark grey), saying what was seen; or when the sources do not match the
// rig's cameras or one fails to open.
LearnColourResult LearnBallColour(const Rig& rig, const std::vector<std::string>& sources,
                                  const LearnColourOptions& options);

// One camera, the named colour chosen (ChooseNamedColour): its shades in this hall learnt from its
// own confirmed flights. The named boxes take the ball's lit part where the hall is dim or the
// ball shaded (a yellow ball in a dim hall: its lit cap, a third of its width); each view is
// measured by coverage on the background model (segment/foreground_finder.h), and its core
// sampled as LearnBallColour does. Throws p4::Error as LearnBallColour.
LearnColourResult LearnNamedColour(const Rig& rig, const std::vector<std::string>& sources,
                                   const std::string& name, const LearnColourOptions& options);

// One camera: no second view tells the ball from whatever else moves, so its colour is chosen
// among named ones instead of learnt: the one whose tracker, over the sources' first seconds,
// takes the most views of confirmed flights (track::TrackInitiator: what flies; a shirt or a
// floor of one of the colours does not). The names come in order of preference and a later one
// must take `later_ratio` times the views of the one before it: the colours' boxes overlap (an
// orange ball's lit side reads yellow, so an orange ball also flies as a yellow one), while a
// yellow ball takes next to no orange views.
struct ChooseColourOptions {
  double max_seconds = 10.0;  // of the sources looked at, from their first set
  double later_ratio = 2.0;   // > 0

  bool IsValid() const { return max_seconds > 0.0 && later_ratio > 0.0; }
};

struct NamedColourChoice {
  std::string name;                                // the choice ("" when none flew)
  std::vector<std::pair<std::string, int>> views;  // each name's views of a confirmed track
  double seconds = 0.0;                            // of the sources looked at
};

// `tracking`: the options to track with (their ball colour and detector are set per name: the
// background model for a white ball, as `--detector auto` does). Throws p4::Error when the
// sources do not match the rig's cameras or one fails to open.
NamedColourChoice ChooseNamedColour(const Rig& rig, const std::vector<std::string>& sources,
                                    const std::vector<std::string>& names,
                                    const track::FrameSetOptions& tracking,
                                    const ChooseColourOptions& options = {});

}  // namespace p4
