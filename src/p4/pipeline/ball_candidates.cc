#include "p4/pipeline/ball_candidates.h"

#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <thread>

#include "p4/core/error.h"
#include "p4/core/table.h"
#include "p4/geometry/sphere_depth.h"
#include "p4/io/video_reader.h"
#include "p4/segment/background_model.h"
#include "p4/segment/blob_finder.h"
#include "p4/segment/colour_learning.h"
#include "p4/segment/foreground_finder.h"
#include "p4/segment/pixel_access.h"
#include "p4/segment/streak_finder.h"

namespace p4 {

namespace {

// The finder's options for the offset search: none of its still candidates, not even those that
// stand alone (a ball held still tells no time; kept, they crowded webcams' offsets: unsync-webcam
// tuning 2 found two offsets almost as good and was taken as in step, 7.2 -> 1790 mm).
segment::StreakFinderOptions StreakFinderForSync() {
  segment::StreakFinderOptions o;
  o.isolated_max_share = -1.0;
  return o;
}

// The centre of what moved in a region: its box's pixels weighted by how far their luma is from
// the background's (the region's own centroid snaps to the 2x2 blocks of the motion mask).
Eigen::Vector2d MovingCentre(const ImageView& image, const segment::BackgroundModel& background,
                             const segment::Region& r) {
  double sw = 0.0, sx = 0.0, sy = 0.0;
  const int x0 = std::max(0, r.x0 - 1), x1 = std::min(background.width(), r.x1 + 1);
  const int y0 = std::max(0, r.y0 - 1), y1 = std::min(background.height(), r.y1 + 1);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double w = std::abs(segment::internal::LumaAt(image, x, y) - background.Luma(x, y));
      sw += w, sx += w * x, sy += w * y;
    }
  }
  return sw > 0.0 ? Eigen::Vector2d(sx / sw, sy / sw) : Eigen::Vector2d(r.cx, r.cy);
}

}  // namespace

bool BallCandidateOptions::IsValid(std::string* error) const {
  if (!(seconds > 0.0) || per_frame < 1 || !(min_diameter_px > 0.0) || !(max_speed_px_s > 0.0) ||
      !(streak_max_fps >= 0.0)) {
    if (error) {
      *error =
          "ball candidates: seconds, per_frame, sizes must be positive, streak_max_fps not "
          "negative";
    }
    return false;
  }
  return ball.IsValid(error);
}

std::vector<std::vector<sync::FrameCandidates>> ReadBallCandidates(
    const Rig& rig, const std::vector<std::string>& sources, const segment::ColorClassSet& classes,
    const BallCandidateOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  if (static_cast<int>(sources.size()) != rig.size()) {
    throw Error(fmt::format("the rig has {} camera(s) but {} source(s) were given", rig.size(),
                            sources.size()));
  }
  const segment::ColorLut lut = classes.BuildLut();
  const uint32_t mask = classes.MaskOf("ball") ? classes.MaskOf("ball") : 0xffffffffu;
  std::vector<std::vector<sync::FrameCandidates>> out(sources.size());
  std::vector<std::string> errors(sources.size());
  const auto read = [&](std::size_t c) {
    try {
      const Camera& camera = rig.cameras[c];
      VideoReader reader(sources[c]);
      if (reader.info().width != camera.width || reader.info().height != camera.height) {
        throw Error(fmt::format("{}: the video is {}x{} but rig camera '{}' is {}x{}", sources[c],
                                reader.info().width, reader.info().height, camera.name,
                                camera.width, camera.height));
      }
      // The ball is no nearer than a metre.
      const double largest = 1.3 * 2.0 * table::kBallRadius * camera.fx;
      const double fps = reader.info().fps > 0.0 ? reader.info().fps : 30.0;
      const double longest_streak = options.max_speed_px_s / fps;
      segment::BlobFinder finder;
      // The ball's size over the table's middle, a little above it (the streaks' template).
      const double diameter =
          SphereDiameterPx(camera, Eigen::Vector3d(0.0, 0.0, 0.2), table::kBallRadius);
      const bool streaks = fps <= options.streak_max_fps && diameter > 0.0;
      segment::StreakFinder streak_finder;
      const segment::StreakFinderOptions streak_finder_options = StreakFinderForSync();
      segment::StreakSearch streak_search;
      std::vector<segment::FoundStreak> found;
      // What differs from a background learnt as the frames come (the colour alone finds
      // banners, shirts and lettering of the ball's colour; with AnyColour, motion alone).
      // (The short-term model alone: with the long-term one, webcam tuning 2's candidates set a
      // camera in step 2.3 ms off and the run lost 5 % recall.)
      segment::BackgroundModel background(camera.width, camera.height, {});
      segment::ForegroundFinder foreground;
      segment::SegmentOptions segment;
      segment.mask = mask;
      segment.max_regions = 64;
      std::vector<segment::Region> regions;
      // Every region's centre in the last frame: what is there again did not move (lettering,
      // lamps, a banner's letters) and is no candidate, however large.
      std::vector<Eigen::Vector2d> last, seen;
      ImageView view;
      TimeNs pts = 0;
      std::optional<TimeNs> first;
      while (reader.ReadView(&view, &pts)) {
        if (!first) first = pts;
        if (ToSeconds(pts - *first) > options.seconds) break;
        int n = 0;
        found.clear();
        if (background.ready()) {
          const segment::BlockMask moving =
              foreground.DifferingBlocks(view, background, {}, options.moving_sigmas, false);
          n = finder.Find(view, lut, {}, segment, &regions, &moving);
          if (streaks) {
            segment::FindStreaks(view, background, options.ball, diameter, streak_finder_options,
                                 {}, &streak_finder, &streak_search, &found);
          }
        }
        background.Update(view);
        sync::FrameCandidates frame{ToSeconds(pts), {}};
        seen.clear();
        for (int k = 0; k < n; ++k) {
          const segment::Region& r = regions[k];
          const Eigen::Vector2d centre = MovingCentre(view, background, r);
          seen.push_back(centre);
          if (static_cast<int>(frame.pixels.size()) >= options.per_frame ||
              r.minor_diameter < options.min_diameter_px || r.minor_diameter > largest ||
              r.major_diameter > r.minor_diameter + longest_streak) {
            continue;
          }
          const bool still = std::any_of(last.begin(), last.end(), [&](const Eigen::Vector2d& p) {
            return (p - centre).norm() < options.still_px;
          });
          if (!still) frame.pixels.push_back(centre);
        }
        // The streaks come beside the regions, not in their places: a camera that exposes
        // briefly sees the ball sharp (its streak hits are the hall's clutter), a webcam's
        // regions are often the hall's clutter and its ball a streak. None on a region taken
        // (the same ball).
        const std::size_t regions_end = frame.pixels.size();
        for (const segment::FoundStreak& f : found) {
          const Eigen::Vector2d p(f.hit.cx, f.hit.cy);
          const bool taken = std::any_of(
              frame.pixels.begin(), frame.pixels.begin() + static_cast<std::ptrdiff_t>(regions_end),
              [&](const Eigen::Vector2d& q) { return (q - p).norm() < diameter; });
          if (!taken) frame.pixels.push_back(p);
        }
        std::swap(last, seen);
        out[c].push_back(std::move(frame));
      }
    } catch (const std::exception& e) {
      errors[c] = e.what();
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t c = 0; c < sources.size(); ++c) threads.emplace_back(read, c);
  for (auto& t : threads) t.join();
  for (const auto& e : errors) {
    if (!e.empty()) throw Error(e);
  }
  return out;
}

sync::RigSyncResult SyncFromSources(const Rig& rig, const std::vector<std::string>& sources,
                                    const segment::ColorClassSet& classes,
                                    const BallCandidateOptions& candidates,
                                    const sync::RigSyncOptions& sync) {
  std::string why;
  if (!sync.IsValid(&why)) throw Error(why);
  return sync::SynchroniseRig(rig, ReadBallCandidates(rig, sources, classes, candidates), sync);
}

std::string DescribeClock(const Camera& camera, const sync::OffsetResult& r, bool reference) {
  const std::string readout =
      camera.clock.line_time_s > 0.0
          ? fmt::format(", rows read out over {:.1f} ms",
                        1e3 * camera.clock.line_time_s * std::max(1, camera.height - 1))
          : std::string();
  if (reference) {
    return fmt::format("{}: the rig's clock (offset {:+.6f} s){}", camera.name,
                       camera.clock.time_offset_s, readout);
  }
  if (!r.found) return fmt::format("{}: not found: {}", camera.name, r.why);
  if (r.in_step) {
    return fmt::format(
        "{}: in step (offset 0 within {:.3f} ms, its sigma x 2.5; {} of {} points "
        "agree, {:.2f} px RMS)",
        camera.name, 2.5e3 * r.sigma_s, r.agreements, r.points, r.rms_px);
  }
  return fmt::format(
      "{}: offset {:+.6f} s +- {:.3f} ms, {}{} ({} of {} points agree, {:.2f} px RMS)", camera.name,
      r.offset_s, 1e3 * r.sigma_s,
      r.rate_fitted ? fmt::format("drift {:+.1f} ppm", 1e6 * (r.rate - 1.0))
                    : std::string("drift not fitted (under 20 s of agreeing play)"),
      readout, r.agreements, r.points, r.rms_px);
}

SyncBall SyncBallOf(const std::optional<ColorClassFile>& file, const std::string& hint) {
  SyncBall ball;
  const bool any = hint == "auto" || hint == "any";
  ball.classes = file ? file->classes : any ? segment::AnyColour() : segment::NamedBall(hint);
  if (file && file->ball) {
    ball.streak = *file->ball;
  } else {
    segment::BallColour::Named(hint, &ball.streak);  // orange for auto and any
  }
  return ball;
}

}  // namespace p4
