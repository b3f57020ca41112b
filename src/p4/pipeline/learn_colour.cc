#include "p4/pipeline/learn_colour.h"

#include <fmt/format.h>

#include <optional>

#include "p4/core/error.h"
#include "p4/core/table.h"
#include "p4/pipeline/frame_set_reader.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/color_classes.h"

namespace p4 {

namespace {

// Reads the sources' sets from their first one for at most `max_seconds`, handing each to
// `take` until it returns false; returns the seconds looked at. Throws p4::Error when the
// sources do not match the rig's cameras or one fails to open.
template <typename Take>
double ReadFirstSeconds(const Rig& rig, const std::vector<std::string>& sources, double max_seconds,
                        Take&& take) {
  if (static_cast<int>(sources.size()) != rig.size()) {
    throw Error(fmt::format("the rig has {} camera(s) but {} source(s) were given", rig.size(),
                            sources.size()));
  }
  FrameSetReader reader(sources, false, RigClocks(rig));
  std::optional<TimeNs> first;
  double seconds = 0.0;
  FrameSet set;
  while (reader.Next(&set)) {
    if (!first) first = set.t;
    seconds = ToSeconds(set.t - *first);
    if (seconds > max_seconds || !take(set)) break;
  }
  return seconds;
}

}  // namespace

namespace {

// The first seconds of the sources tracked by `tracker`; the core of every view the filter took
// at once (a confirmed track of at least min_cameras views) of a ball flying over the table is a
// sample of its colour, whatever else moves in those pictures a sample of what it is not; the
// colour learnt from them. Throws p4::Error when too little was seen or, unless the tracker's
// colour was named (its boxes vouch for a colour: a yellow ball in a dim hall reads Y 84, chroma
// 27 from grey), what flew is a dark grey.
LearnColourResult SampleFlights(const Rig& rig, const std::vector<std::string>& sources,
                                int min_cameras, const segment::ColorClassSet* named,
                                const LearnColourOptions& options,
                                track::FrameSetTracker* tracker) {
  segment::ColourSamples samples;
  LearnColourResult result;
  bool new_track = false;
  result.seconds = ReadFirstSeconds(rig, sources, options.max_seconds, [&](const FrameSet& set) {
    const track::FrameSetResult r = tracker->Process(set.t, set.images, set.times);
    // Only views the filter took at once: the track is confirmed, the view is the ball's.
    if (!r.state || !r.state->measured || r.tentative || !r.measurement ||
        r.measurement->cameras < min_cameras) {
      return true;
    }
    if (r.new_track) new_track = true;  // a tracklet confirmed
    // Over the table and above it, where the ball in play flies and the players' shoes, legs
    // and bodies do not; and flying (a track that has come to rest on two things that happen to
    // meet across the views is not the ball).
    const Eigen::Vector3d& p = r.measurement->position;
    if (std::abs(p.x()) > table::kHalfLength || std::abs(p.y()) > table::kHalfWidth ||
        p.z() < table::kBallRadius || p.z() > options.max_height ||
        r.state->velocity.norm() < options.min_speed) {
      return true;
    }
    if (new_track) ++result.tracks, new_track = false;  // its first view sampled
    for (const track::Detection& d : r.detections) {
      // A faint streak's pixels are mostly the background's: no sample of the ball's colour.
      if (!d.accepted || d.streak || !set.images[d.camera]) continue;
      samples.AddDisc(*set.images[d.camera], d.observed, d.diameter_px, options.learning,
                      &tracker->background(d.camera));
      ++result.views;
      // What else moves in this picture (arms, heads, shirts) is what the colours must not take.
      samples.AddMoving(*set.images[d.camera], tracker->background(d.camera),
                        std::span<const Eigen::Vector2d>(&d.observed, 1),
                        options.moving_clear * d.diameter_px, options.learning);
    }
    // Enough seen: stop early.
    return result.views < options.min_views || result.tracks < options.min_tracks ||
           samples.size() < 2 * options.learning.min_samples;
  });
  std::string why;
  if (result.views == 0 || !samples.Learn(options.learning, &result.colour, &why)) {
    throw Error(fmt::format(
        "--ball auto: the ball was not seen flying in the first {:.1f} s of the sources ({} "
        "view(s) in {} track(s){}{}); give its colour with --ball orange|white|yellow or "
        "--classes FILE",
        result.seconds, result.views, result.tracks, why.empty() ? "" : ": ", why));
  }
  if (named) result.named_taken = segment::TakenShare(named->classes, samples.samples());
  if (!named && result.colour.ball.IsGrey() && !result.colour.ball.IsWhite()) {
    const segment::Yuv& lit = result.colour.ball.lit;
    throw Error(fmt::format(
        "--ball auto: what flew over the table in the first {:.1f} s is a dark grey (lit YUV "
        "{:.0f} {:.0f} {:.0f}), no ball's colour (a shadow, a shoe); give its colour with --ball "
        "orange|white|yellow or --classes FILE",
        result.seconds, lit.y, lit.u, lit.v));
  }
  return result;
}

}  // namespace

bool LearnColourOptions::IsValid(std::string* error) const {
  if (!(max_seconds > 0.0) || min_views < 1 || min_tracks < 1 || !(moving_clear >= 0.0) ||
      !(keep_named_share >= 0.0 && keep_named_share <= 1.0)) {
    if (error) {
      *error =
          "colour learning: seconds, views and tracks must be positive, moving_clear >= 0, "
          "keep_named_share in [0, 1]";
    }
    return false;
  }
  return learning.IsValid(error) && tracking.IsValid(error);
}

LearnColourResult LearnBallColour(const Rig& rig, const std::vector<std::string>& sources,
                                  const LearnColourOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  track::FrameSetOptions tracking = options.tracking;
  tracking.use_background = false;
  tracking.measure_on_background = false;
  tracking.mask_with_background = true;  // whatever differs from the hall, of any colour
  tracking.confirm_tracks = true;
  tracking.mask_sigmas = options.mask_sigmas;
  tracking.mask_grow = false;  // every colour passes: the mask alone draws the ball's outline
  // A small view here is a small thing that moves, not the lit part of a shaded ball that a
  // ball's colour tables took: no view is measured again at the ball's size.
  tracking.whole_fragments = false;
  // Nor looked for along another view's epipolar line by its edge alone: the colour is learnt
  // from what the background mask outlines.
  tracking.search_epipolars = false;
  // The point only tells which views fly together: no centre moved back from a shaded side (its
  // millimetres change which flights confirm first and so the samples: white tuning 4 learnt
  // another colour with it, 95.3 -> 90.6 % recall, 0 -> 4.1 % false rows).
  tracking.shade_correction = false;
  // Nor a short view measured again by the outline of the ball's size: a small region here is
  // a small thing that moves (learnt with it, sports tuning 7's classes came from 199 views
  // instead of 344 and let a false track through, 12.5 % false rows).
  tracking.outline_short_views = false;
  // A pair whose point a third camera sees in a region of another size is no ball here: that
  // region is most often the body whose pieces the pair took, and the samples must be pure.
  tracking.misfit_view_rejects_pair = true;
  // The short-term background alone: its "what else moves" leaves out a player who stands
  // still. With the long-term model taken back wherever such a player stirs, their skin and
  // shirts came back among the other moving pixels and took ball colours with them (sports
  // tuning 1: classes that took 95.2 % of the ball's pixels instead of 99.8 %; 2: 60 views of
  // the ball instead of 247).
  tracking.background.long_term = false;
  // Its window stays on what it finds: everything that moves is a region of some size, and a
  // whole-image search after every hit lets the colour-free tracker jump to arms and shirts
  // (sports tuning seed 23: the learnt colour took 55 % of the moving pixels instead of 6 %).
  tracking.roi_needs_size = false;
  // Every moving thing is a candidate (arms, legs, shirts): more of them than for a coloured ball.
  tracking.candidates_per_camera =
      std::max(tracking.candidates_per_camera, options.candidates_per_camera);
  // Its views are judged as a region at a predicted point is (max_size_ratio): the mask outlines
  // whatever moves, not the ball's colour, and which flight confirms first decides the samples
  // (with the tracker's bound for views, sports tuning 3 learnt another colour: 2.5 -> 12.6 mm).
  tracking.max_view_size_ratio = tracking.max_size_ratio;
  tracking.view_size_margin_sigmas = 0.0;
  track::FrameSetTracker tracker(rig, segment::AnyColour(), tracking);
  return SampleFlights(rig, sources, 2, nullptr, options, &tracker);
}

LearnColourResult LearnNamedColour(const Rig& rig, const std::vector<std::string>& sources,
                                   const std::string& name, const LearnColourOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  track::FrameSetOptions tracking = options.tracking;
  segment::BallColour::Named(name, &tracking.ball_colour);
  tracking.confirm_tracks = true;
  tracking.use_background = false;
  tracking.mask_with_background = false;
  // The named colour's boxes find the ball (the lit part of a shaded one); the background model
  // outlines it, shaded side and all: each view is measured by coverage on it.
  tracking.measure_on_background = true;
  tracking.background.long_term = false;  // as the learner above (what else moves)
  const segment::ColorClassSet classes = segment::NamedBall(name);
  track::FrameSetTracker tracker(rig, classes, tracking);
  return SampleFlights(rig, sources, 1, &classes, options, &tracker);
}

NamedColourChoice ChooseNamedColour(const Rig& rig, const std::vector<std::string>& sources,
                                    const std::vector<std::string>& names,
                                    const track::FrameSetOptions& tracking,
                                    const ChooseColourOptions& options) {
  if (!options.IsValid()) {
    throw Error("choosing the ball's colour: seconds and the later names' ratio must be positive");
  }
  NamedColourChoice choice;
  int best = 0;
  for (const std::string& name : names) {
    track::FrameSetOptions per_name = tracking;
    segment::BallColour::Named(name, &per_name.ball_colour);
    per_name.use_background = per_name.use_background || name == "white";
    per_name.confirm_tracks = true;
    track::FrameSetTracker tracker(rig, segment::NamedBall(name), per_name);
    int views = 0;
    choice.seconds = ReadFirstSeconds(rig, sources, options.max_seconds, [&](const FrameSet& set) {
      const track::FrameSetResult r = tracker.Process(set.t, set.images, set.times);
      // A tracklet's points become rows when it is confirmed; a row taken at once is one.
      views += static_cast<int>(r.revisions.size());
      if (r.state && r.state->measured && !r.tentative) ++views;
      return true;
    });
    choice.views.emplace_back(name, views);
    if (views > 0 && (choice.name.empty() || views > options.later_ratio * best)) {
      best = views;
      choice.name = name;
    }
  }
  return choice;
}

}  // namespace p4
