#include "p4/track/frame_set_tracker.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "p4/core/table.h"
#include "p4/geometry/epipolar.h"
#include "p4/geometry/sphere_depth.h"
#include "p4/geometry/triangulation.h"
#include "p4/segment/ball_edge.h"
#include "p4/segment/ball_measure.h"
#include "p4/track/flight_model.h"
#include "p4/track/rts_smoother.h"

namespace p4::track {

bool FrameSetOptions::IsValid(std::string* error) const {
  if (!segment.IsValid(error) || !tracker.IsValid(error) || !initiator.IsValid(error)) return false;
  if (!(contact_max_m >= 0.0) || !(contact_flight_max_s > 0.0)) {
    if (error) *error = "contact_max_m must be >= 0 and contact_flight_max_s positive";
    return false;
  }
  if (!(bridge_span_s >= 0.0) || !(bridge_max_rms > 0.0)) {
    if (error) *error = "bridge_span_s must be >= 0 and bridge_max_rms positive";
    return false;
  }
  if (!(off_colour_residual > 0.0)) {
    if (error) *error = "off_colour_residual must be positive";
    return false;
  }
  if (!(still_and_moving_max_speed_share >= 0.0 && still_and_moving_max_speed_share <= 1.0)) {
    if (error) *error = "still_and_moving_max_speed_share must lie in [0, 1]";
    return false;
  }
  if (candidates_per_camera < 1 || !(epipolar_px > 0.0) || !(reprojection_px > 0.0)) {
    if (error) *error = "candidates, epipolar and reprojection bounds must be positive";
    return false;
  }
  if (!(max_size_ratio > 1.0) || !(max_view_size_ratio > 1.0) ||
      !(view_size_margin_sigmas >= 0.0)) {
    if (error) *error = "max_size_ratio and max_view_size_ratio must be above 1, the margin >= 0";
    return false;
  }
  if (!(pixel_sigma > 0.0) || !(centre_sigma_share >= 0.0) || !(misfit_sigma_share >= 0.0)) {
    if (error)
      *error = "pixel_sigma must be positive, centre_sigma_share and misfit_sigma_share >= 0";
    return false;
  }
  if (!(motion_max_gap_s > 0.0) || !(motion_max_px_s > 0.0)) {
    if (error) *error = "motion_max_gap_s and motion_max_px_s must be positive";
    return false;
  }
  if (!(outline_short_ratio > 0.0 && outline_short_ratio <= 1.0) ||
      !(outline_min_ratio >= 0.0 && outline_min_ratio < outline_short_ratio) ||
      !(outline_shift_margin_px >= 0.0) || !(outline_sided_shift_share >= 0.0) ||
      !(outline_min_diameter_px >= 0.0)) {
    if (error) {
      *error =
          "outline_short_ratio must be in (0, 1], outline_min_ratio in [0, outline_short_ratio), "
          "outline_shift_margin_px, outline_sided_shift_share and outline_min_diameter_px at least "
          "0";
    }
    return false;
  }
  if (!(past_end_min_coast_s >= 0.0)) {
    if (error) *error = "past_end_min_coast_s must be >= 0";
    return false;
  }
  if (roi_min_px < 8 || roi_max_px < roi_min_px || roi_max_missed < 0) {
    if (error) *error = "ROI: need sizes 8 <= min <= max and roi_max_missed >= 0";
    return false;
  }
  if (!background.IsValid(error) || !foreground.IsValid(error) || !ball_colour.IsValid(error) ||
      !edge.IsValid(error) || !shade.IsValid(error) || !outline.IsValid(error) ||
      !streak.IsValid(error) || !streak_finder.IsValid(error) || !disc_search.IsValid(error)) {
    return false;
  }
  if (!(split_max_moving >= 0.0 && split_max_moving <= 1.0) || !(split_max_elongation >= 1.0)) {
    if (error) *error = "split_max_moving must be in [0, 1] and split_max_elongation at least 1";
    return false;
  }
  if (search_views_per_camera < 0 || !epipolar.IsValid(error)) {
    if (error && search_views_per_camera < 0) *error = "search_views_per_camera must be >= 0";
    return false;
  }
  if (!(still_max_motion_px >= 0.0)) {
    if (error) *error = "still_max_motion_px must be at least 0";
    return false;
  }
  if (!(blur_size_share >= 1.0) || !(blur_motion_share >= 1.0) || !(blur_margin_px >= 0.0)) {
    if (error) {
      *error =
          "blur_size_share and blur_motion_share must be at least 1, blur_margin_px at least 0";
    }
    return false;
  }
  if (!(streak_min_frame_s > 0.0)) {
    if (error) *error = "streak_min_frame_s must be positive";
    return false;
  }
  if (!(backfill_px >= 0.0) || backfill_max_missed < 0 || !(backfill_contact_mps >= 0.0)) {
    if (error)
      *error =
          "backfill_px, backfill_max_missed and backfill_contact_mps must be at least 0 (0 px: no "
          "back-fill)";
    return false;
  }
  if (!(single_view_depth_sigma > 0.0) || !(single_view_max_depth_sigma > 0.0) ||
      !(lone_view_depth_sigma >= 0.0) || !(lone_view_gate_chi2 > 0.0) ||
      !(lone_view_image_sigma > 0.0) || !(lone_view_consistency_chi2 > 0.0)) {
    if (error) {
      *error =
          "single_view_depth_sigma, single_view_max_depth_sigma and the lone views' gates "
          "must be positive, lone_view_depth_sigma at least 0";
    }
    return false;
  }
  if (!(hall_half_length > table::kHalfLength) || !(hall_half_width > table::kHalfWidth) ||
      !(hall_max_z > 0.0)) {
    if (error) *error = "the hall must hold the table and reach above it";
    return false;
  }
  if (threads < 1 || threads > 64) {
    if (error) *error = "threads must be 1-64";
    return false;
  }
  return true;
}

namespace {

// The initiator judges a tracklet's fall as the tracker judges its track's.
TrackInitiatorOptions WithTrackerFall(TrackInitiatorOptions initiator,
                                      const TrackerOptions& tracker) {
  initiator.fall = tracker.fall;
  return initiator;
}

}  // namespace

FrameSetTracker::FrameSetTracker(const Rig& rig, const segment::ColorClassSet& classes,
                                 const FrameSetOptions& options)
    : rig_(rig),
      lut_(classes.BuildLut()),
      options_(options),
      finders_(rig.cameras.size()),
      backgrounds_(rig.cameras.size()),
      foreground_finders_(rig.cameras.size()),
      coverage_(rig.cameras.size()),
      measured_(rig.cameras.size()),
      static_spots_(rig.cameras.size()),
      faint_votes_(rig.cameras.size()),
      regions_(rig.cameras.size()),
      streak_searches_(rig.cameras.size()),
      streak_finders_(rig.cameras.size()),
      last_image_time_(rig.cameras.size()),
      frame_period_s_(rig.cameras.size(), 0.0),
      ball_coloured_hall_(rig.cameras.size(), 0),
      tracker_options_(options.tracker),
      initiator_(WithTrackerFall(options.initiator, options.tracker)) {
  // New tracks come from the initiator: a refused measurement must not restart the filter.
  if (options.confirm_tracks) tracker_options_.restart_on_refusal = false;
  if (options.confirm_tracks && rig.size() >= 2) {
    tracker_options_.one_view_holds_track = false;
    // The lone views' rows wait as long as the hold (the initiator's span): so do the steps.
    if (options.lone_view_depth_sigma > 0.0) {
      tracker_options_.history_s = options.initiator.max_span_s;
    }
  }
  tracker_ = BallTracker(tracker_options_);
  options_.segment.mask = classes.MaskOf("ball");
  // The epipolar search's hall and ball are the tracker's.
  options_.epipolar.half_length = options_.hall_half_size.x();
  options_.epipolar.half_width = options_.hall_half_size.y();
  options_.epipolar.max_z = options_.hall_half_size.z();
  options_.epipolar.floor_z = table::kFloorZ - 0.02;
  options_.epipolar.ball_radius = table::kBallRadius;
  triangulation_.pixel_sigma = options_.pixel_sigma;
  triangulation_.ray_sigma_m = options_.centre_sigma_share * table::kBallDiameter;
  if (options.threads > 1 && rig.size() > 1) {
    pool_ = std::make_unique<CameraPool>(std::min(options.threads, rig.size()));
  }
}

namespace {

// A view measured again: its centre as its camera saw it, keeping its shift to the set's time
// (MoveToSetTime), and its diameter; a disc now (its width is its diameter).
void Remeasure(const Eigen::Vector2d& observed, double diameter_px, Detection* d) {
  const Eigen::Vector2d shift = d->pixel - d->observed;
  d->observed = observed;
  d->pixel = observed + shift;
  d->diameter_px = diameter_px;
  d->edge_width_px = 0.0;
}

double ExpectedDiameterPx(const Camera& camera, const Eigen::Vector3d& point) {
  return SphereDiameterPx(camera, point, table::kBallRadius);
}

// The prediction's spread in camera's image: its largest position sigma (covariance, m) across
// the ray at its depth, px. NaN behind the camera.
double PredictionSigmaPx(const Camera& camera, const Eigen::Vector3d& predicted,
                         const Eigen::Matrix3d& covariance) {
  const double depth = (camera.cam_from_world * predicted).z();
  if (!(depth > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return camera.fx * std::sqrt(std::max(0.0, covariance.diagonal().maxCoeff())) / depth;
}

// Whether the edge fit measured a width across (a disc, or a short streak within
// max_elongation): its minor diameter is then the ball's.
bool EdgeGivesDiameter(const segment::EdgeCentre& e, double max_elongation) {
  return e.minor_diameter > 0.0 && e.major_diameter <= max_elongation * e.minor_diameter;
}

// A flight's state and covariance carried over dt seconds, back or forth: gravity and drag in
// steps of at most 4 ms (the midpoint rule: well under a millimetre), the covariance as uniform
// motion (the position's spread grows with the velocity's); `covariance` may be null.
void CarryFlight(const KalmanOptions& kalman, double dt, Vector6d* state,
                 Matrix6d* covariance = nullptr) {
  const int n = static_cast<int>(std::ceil(std::abs(dt) / 0.004));
  const double h = dt / std::max(1, n);
  for (int k = 0; k < n; ++k) *state = DragStep(*state, h, kalman.gravity, kalman.drag_per_mass);
  if (!covariance) return;
  Matrix6d f = Matrix6d::Identity();
  f.topRightCorner<3, 3>() = dt * Eigen::Matrix3d::Identity();
  *covariance = f * *covariance * f.transpose();
}

// Where two flights come nearest, searched from u0 to u1 (both included) in steps of `step`:
// flight a's state at ta and b's at tb, each carried to the time. dv: a's velocity less b's
// there (a contact, where it is large).
struct Meeting {
  double distance = 0.0;  // m
  TimeNs t = 0;
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();
};
Meeting FlightsMeet(const KalmanOptions& kalman, Vector6d a, TimeNs ta, Vector6d b, TimeNs tb,
                    TimeNs u0, TimeNs u1, TimeNs step) {
  CarryFlight(kalman, ToSeconds(u0 - ta), &a);
  CarryFlight(kalman, ToSeconds(u0 - tb), &b);
  Meeting m{(a.head<3>() - b.head<3>()).norm(), u0, a.tail<3>() - b.tail<3>()};
  for (TimeNs u = u0 + step; u <= u1; u += step) {
    CarryFlight(kalman, ToSeconds(step), &a);
    CarryFlight(kalman, ToSeconds(step), &b);
    const double d = (a.head<3>() - b.head<3>()).norm();
    if (d < m.distance) m = {d, u, a.tail<3>() - b.tail<3>()};
  }
  return m;
}

// A flight's position where the back-fill places views on it is known to this at best (m): the
// points it was fitted to are known to millimetres.
constexpr double kFlightSigmaFloor = 0.003;

// Steps `filter` through the tracklet's points [first, last); each measured state whose
// time-stamp `revise` accepts becomes a revision of it.
void ReplayPoints(const Tracklet& tracklet, std::size_t first, std::size_t last,
                  BallTracker* filter, const std::function<bool(TimeNs)>& revise,
                  FrameSetResult* result) {
  for (std::size_t i = first; i < last; ++i) {
    const TrackletPoint& p = tracklet.points[i];
    const auto state = filter->Step(p.t, p.measurement);
    if (state && state->measured && revise(p.t)) {
      result->revisions.push_back({p.t, p.measurement, *state, p.detections});
    }
  }
}

// Camera c's view of a ball of `diameter` px centred at `pixel` (as seen: at the set's time), its
// area the disc's.
Detection DiscView(int c, const Eigen::Vector2d& pixel, double diameter) {
  Detection d{c, pixel, diameter, static_cast<int>(std::lround(M_PI / 4.0 * diameter * diameter)),
              false};
  d.observed = d.pixel;
  return d;
}

// Camera c's view of a faint streak: its middle, the ball's diameter given to it.
Detection StreakDetection(int c, const segment::StreakHit& hit, double diameter) {
  Detection d = DiscView(c, {hit.cx, hit.cy}, diameter);
  d.streak = true;
  d.colour_residual = hit.colour_residual;
  return d;
}

}  // namespace

bool FrameSetTracker::StillAndMoving(const Hypothesis& h,
                                     const std::vector<std::vector<Detection>>& candidates,
                                     const Eigen::Vector3d& position) const {
  const double share = options_.still_and_moving_max_speed_share;
  if (!(share > 0.0)) return false;
  bool moving = false, narrow = false;
  for (const auto& [c, k] : h.members) {
    if (!candidates[c][k].still) {
      moving = true;
      continue;
    }
    // The speed across the camera's ray under which the ball stays within static_px over its
    // frame period: still, the ball flies within asin(that / speed) of the ray.
    const Camera& camera = rig_.cameras[c];
    const double depth = (camera.cam_from_world * position).z();
    const double period = frame_period_s_[c];
    if (!(depth > 0.0) || !(period > 0.0)) continue;
    const double still_speed = options_.static_px * depth / (camera.fx * period);
    narrow = narrow || still_speed <= share * options_.initiator.min_travel_speed;
  }
  return moving && narrow;
}

bool FrameSetTracker::SearchesStreaks(int c) const {
  switch (options_.streaks) {
    case FrameSetOptions::Streaks::kOff:
      return false;
    case FrameSetOptions::Streaks::kOn:
      return true;
    case FrameSetOptions::Streaks::kAuto:
      return frame_period_s_[c] >= options_.streak_min_frame_s;
  }
  return false;
}

std::optional<Detection> FrameSetTracker::StreakView(int c, const ImageView& image,
                                                     const Eigen::Vector3d& predicted,
                                                     const Eigen::Vector3d& velocity,
                                                     const Eigen::Matrix3d& covariance) {
  const Camera& camera = rig_.cameras[c];
  const double period = frame_period_s_[c];
  if (!(period > 0.0)) return std::nullopt;
  // The ball's path over a whole frame period about its predicted place: the exposure is some
  // part of it, centred on the image's time.
  const auto mid = camera.Project(predicted);
  const auto a = camera.Project(predicted - 0.5 * period * velocity);
  const auto b = camera.Project(predicted + 0.5 * period * velocity);
  if (!mid || !a || !b) return std::nullopt;
  const double diameter = ExpectedDiameterPx(camera, predicted);
  const Eigen::Vector2d path = *b - *a;
  if (!(diameter > 0.0)) return std::nullopt;
  // Shorter than two diameters over a whole frame: no faint streak, but a camera that looks for
  // them (a webcam) may still miss the ball in its colour tables: a ball of 3-4 px keeps little of
  // its chroma through 4:2:0 and the encoder. The same matched filter then looks for a disc.
  segment::StreakSearchOptions o = options_.streak;
  o.search_px = std::clamp(3.0 * PredictionSigmaPx(camera, predicted, covariance),
                           std::min(4.0, o.search_px), o.search_px);
  const auto hit = streak_searches_[c].Find(image, backgrounds_[c], options_.ball_colour, mid->x(),
                                            mid->y(), path.x(), path.y(), path.norm(), diameter, o);
  if (!hit) return std::nullopt;
  Detection d = StreakDetection(c, *hit, diameter);
  d.disc = path.norm() < 2.0 * diameter;
  return d;
}

std::optional<Detection> FrameSetTracker::MergedDiscView(int c, const ImageView& image,
                                                         const Eigen::Vector3d& predicted,
                                                         const Eigen::Vector2d& px, double expected,
                                                         const Eigen::Matrix3d& covariance) {
  const Camera& camera = rig_.cameras[c];
  const double spread = PredictionSigmaPx(camera, predicted, covariance);
  if (std::isnan(spread)) return std::nullopt;
  const double search = std::clamp(3.0 * spread, 2.0, expected);
  segment::CoverageRegion m;
  if (!foreground_finders_[c].FindDisc(image, backgrounds_[c], options_.ball_colour, px.x(), px.y(),
                                       search, expected, ForegroundWithTables(),
                                       options_.disc_search, &m)) {
    return std::nullopt;
  }
  Detection d{c, {m.region.cx, m.region.cy}, expected, m.region.area, false};
  d.by_coverage = true;
  d.in_merged = true;
  d.cut = m.region.touches_border;
  d.length_px = expected;
  d.observed = d.pixel;
  return d;
}

segment::ForegroundOptions FrameSetTracker::ForegroundWithTables() const {
  segment::ForegroundOptions o = options_.foreground;
  o.lut = &lut_;
  o.lut_mask = options_.segment.mask;
  return o;
}

void FrameSetTracker::StreakViews(int c, const ImageView& image, std::vector<Detection>* out) {
  // The ball's size over the table's middle, a little above it.
  const double diameter = ExpectedDiameterPx(rig_.cameras[c], Eigen::Vector3d(0.0, 0.0, 0.2));
  std::vector<segment::FoundStreak> found;
  segment::FindStreaks(image, backgrounds_[c], options_.ball_colour, diameter,
                       options_.streak_finder, options_.streak, &streak_finders_[c],
                       &streak_searches_[c], &found);
  for (const segment::FoundStreak& s : found) {
    out->push_back(StreakDetection(c, s.hit, s.diameter_px));
    // The finder keeps a streak that stands alone where one was in the last frame (a slow
    // ball); measured to a quarter pixel, one within static_px of that place is still.
    out->back().still = SpotCount(c, out->back().pixel) > 1;
  }
}

std::optional<segment::CoverageRegion> FrameSetTracker::MeasureOnBackground(
    int c, const ImageView& image, const segment::Region& r) {
  segment::CoverageRegion m;
  const segment::Roi window{r.x0 - 3, r.y0 - 3, r.x1 + 3, r.y1 + 3};
  if (foreground_finders_[c].Measure(image, backgrounds_[c], options_.ball_colour, window,
                                     options_.foreground, &m) &&
      std::hypot(m.region.cx - r.cx, m.region.cy - r.cy) < 0.5 * r.diameter + 2.0) {
    return m;
  }
  return std::nullopt;
}

bool FrameSetTracker::TooLargeForBall(const segment::Region& r, double largest) const {
  return r.area > options_.max_area_px || r.minor_diameter > largest;
}

int FrameSetTracker::SplitMerged(int c, const ImageView& image, int found, double largest,
                                 bool measured) {
  std::vector<segment::Region>& regions = regions_[c];
  const segment::BackgroundModel& background = backgrounds_[c];
  // Too large for the ball in this camera (nearer than a metre it is never seen), and mostly
  // as the background (a moving shirt of the ball's colour would split into ball-sized pieces).
  std::vector<segment::Roi> large, merged;
  for (int k = 0; k < found; ++k) {
    const segment::Region& r = regions[k];
    if (TooLargeForBall(r, largest)) large.push_back({r.x0, r.y0, r.x1, r.y1});
  }
  if (large.empty()) return -1;
  const segment::BlockMask blocks = foreground_finders_[c].DifferingBlocksWithin(
      image, background, large, options_.mask_sigmas, options_.mask_grow, options_.split_max_moving,
      &merged);
  if (merged.empty()) return -1;
  // The floor's pieces that differ (shadows, feet) must not crowd the ball out.
  segment::SegmentOptions more = options_.segment;
  more.max_regions = 4 * more.max_regions;
  const int n = finders_[c].Find(image, lut_, {}, more, &regions, &blocks);
  // Outside the boxes the regions are those found before. Inside, a piece is the ball only if it
  // differs from the background as the ball would (measured by coverage) and is round (an arm or
  // a shirt's edge that moved is long).
  std::vector<std::optional<segment::CoverageRegion>>& coverage = measured_[c];
  coverage.clear();
  int kept = 0;
  for (int k = 0; k < n; ++k) {
    const segment::Region& r = regions[k];
    const bool within = std::any_of(merged.begin(), merged.end(),
                                    [&](const auto& m) { return m.Contains(r.cx, r.cy); });
    std::optional<segment::CoverageRegion> m;
    if (within || measured) m = MeasureOnBackground(c, image, r);
    if (within && (!m || m->region.major_diameter >
                             options_.split_max_elongation * m->region.minor_diameter)) {
      continue;
    }
    regions[kept++] = r;
    coverage.push_back(m);
  }
  regions.resize(kept);
  return kept;
}

void FrameSetTracker::SearchCamera(int c, const ImageView& image,
                                   const std::optional<Eigen::Vector3d>& predicted,
                                   const std::optional<Eigen::Vector3d>& velocity,
                                   const Eigen::Matrix3d& covariance, bool window,
                                   CameraSearch* search_out, std::vector<Detection>* out) {
  std::vector<segment::Region>& regions = regions_[c];
  const Camera& camera = rig_.cameras[c];
  CameraSearch& search = *search_out;
  search.present = true;
  // The window around the prediction: searched first, or (a coasting track's) only a bound.
  segment::Roi stale;
  if (options_.use_roi && predicted) {
    const auto px = camera.Project(*predicted);
    if (px) {
      const double d = ExpectedDiameterPx(camera, *predicted);
      const int size = std::clamp(static_cast<int>(std::ceil(4.0 * d + 16.0)), options_.roi_min_px,
                                  options_.roi_max_px);
      (window ? search.roi : stale) =
          segment::Roi::Around(px->x(), px->y(), size, size, camera.width, camera.height);
    }
  }
  const std::size_t first_out = out->size();
  segment::BackgroundModel& background = backgrounds_[c];
  const bool streaks = SearchesStreaks(c);
  // split_merged: in cameras whose colour tables have found a region too large for the ball (a
  // floor or banner of its colour), whose frame period is known and that look for no streaks (a
  // ball blurred over a long exposure differs from the background by less than its noise, and
  // would be cut out with the floor). Only they pay for the background model it needs.
  const auto splits = [&] {
    return options_.split_merged && ball_coloured_hall_[c] && frame_period_s_[c] > 0.0 && !streaks;
  };
  const auto keeps_background = [&] {
    return options_.use_background || options_.measure_on_background ||
           options_.mask_with_background || splits() || streaks;
  };
  const auto sized_background = [&] {
    if (background.width() != (image.width & ~1) || background.height() != (image.height & ~1)) {
      background = segment::BackgroundModel(image.width, image.height, options_.background);
    }
  };
  if (keeps_background()) sized_background();
  const bool on_background = options_.use_background && background.ready();
  // The colour tables find; the background only measures (centre and size by coverage).
  const bool measure_only =
      !options_.use_background && options_.measure_on_background && background.ready();
  // Regions found again on what differs from the background (split_merged): by coverage.
  bool split = false;
  segment::ForegroundFinder& foreground = foreground_finders_[c];
  std::vector<segment::CoverageRegion>& coverage = coverage_[c];
  coverage.clear();
  const bool masked = options_.mask_with_background && background.ready();
  // The colour tables first (paper §3.4): in the predicted window, else the whole image. On a
  // known background a colour region must also differ from it (lamps, banners, lines, a ball
  // lying on the floor do not) and is measured by its coverage; what differs from the background
  // with the ball's colour mixed in (a blurred streak, a ball of 3 px, a shaded or white ball)
  // joins them (`both` below).
  // The tables kept as many regions as they keep (SegmentOptions::max_regions) and were searched
  // again on what differs from the background (mask_when_crowded).
  bool crowded = false;
  const auto colour_search = [&](const segment::Roi& roi, bool mask) {
    segment::BlockMask blocks;
    const auto find = [&] {
      if (mask) {
        blocks = foreground.DifferingBlocks(image, background, roi, options_.mask_sigmas,
                                            options_.mask_grow);
      }
      return finders_[c].Find(image, lut_, roi, options_.segment, &regions,
                              mask ? &blocks : nullptr);
    };
    int n = find();
    // The tables keep their largest regions only: where the hall has more of the ball's colour
    // than that (a white hall's lines, lamps and lettering), the ball may be among those left
    // out. Then only what differs from the background is searched again (with 2+ cameras: one
    // camera cannot refuse the players' moving pieces that come with it).
    if (options_.mask_when_crowded && rig_.size() >= 2 && !mask &&
        n >= options_.segment.max_regions && background.ready()) {
      mask = true;
      crowded = true;
      n = find();
    }
    if (!measure_only && !split && !on_background) return n;
    measured_[c].assign(n, std::nullopt);
    for (int k = 0; k < n; ++k) measured_[c][k] = MeasureOnBackground(c, image, regions[k]);
    if (!on_background) return n;
    coverage.clear();
    for (const auto& m : measured_[c]) {
      if (m) coverage.push_back(*m);
    }
    return static_cast<int>(coverage.size());
  };
  const auto background_search = [&](const segment::Roi& roi) {
    segment::ForegroundOptions sized = ForegroundWithTables();
    sized.max_diameter_px = std::min(sized.max_diameter_px, 2.0 * table::kBallRadius * camera.fx);
    return foreground.Find(image, background, options_.ball_colour, roi, sized, &coverage);
  };
  // On a known background both detectors look: the colour tables' regions that differ from it,
  // then what differs with the ball's colour mixed in and is not one of those (a white hall has
  // white regions everywhere; the ball must not wait for them to go).
  const auto both = [&](const segment::Roi& roi, bool mask) {
    const int from_tables = colour_search(roi, mask);
    if (!on_background) return from_tables;
    std::vector<segment::CoverageRegion> merged(coverage.begin(), coverage.begin() + from_tables);
    const int more = background_search(roi);
    for (int k = 0; k < more; ++k) {
      const segment::Region& r = coverage[k].region;
      const bool known =
          std::any_of(merged.begin(), merged.begin() + from_tables, [&](const auto& m) {
            return std::hypot(m.region.cx - r.cx, m.region.cy - r.cy) <
                   0.5 * m.region.diameter + 1.0;
          });
      if (!known) merged.push_back(coverage[k]);
    }
    coverage = std::move(merged);
    return static_cast<int>(coverage.size());
  };
  // The widest the ball can be in this camera (no nearer than a metre; motion blur lengthens it,
  // never widens it).
  const double largest = 2.0 * table::kBallRadius * camera.fx;
  const bool from_colour = !on_background;
  const bool splitting = splits() && from_colour && !masked;
  const auto by_coverage = [&](int k) {
    return !from_colour || ((measure_only || split) && measured_[c][k].has_value());
  };
  const auto region_of = [&](int k) -> const segment::Region& {
    return !from_colour ? coverage[k].region
                        : (by_coverage(k) ? measured_[c][k]->region : regions[k]);
  };
  int found = 0;
  bool disc_seen = false;  // the ball found inside a larger region where predicted
  if (!search.roi.empty()) {
    found = both(search.roi, masked);
    // The window holds the ball only if a region there is the ball's size at the predicted point
    // (after a hit the filter still sends the ball on, into the player's arm): else the whole
    // image is searched. A region that is part of the hall (a second ball lying on the floor,
    // dropped below) does not hold it.
    const double expected = ExpectedDiameterPx(camera, *predicted);
    const auto holds_ball = [&] {
      for (int k = 0; k < found; ++k) {
        if (IsStaticSpot(c, {region_of(k).cx, region_of(k).cy})) continue;
        if (SizeFits(region_of(k).minor_diameter, expected)) return true;
      }
      return false;
    };
    bool sized = holds_ball();
    // Nothing of its size: the ball may have merged with a floor or banner of its colour; what
    // differs from the background there is not the floor.
    if (!sized && splitting && background.ready()) {
      split = true;  // by coverage: the mask's blocks take some floor too
      found = both(search.roi, true);
      sized = holds_ball();
    }
    // A region larger than the ball where it is predicted, and none of its size and length
    // there: the ball may meet a line, an arm or a shirt's edge of its colour (a bar as high as
    // the ball joined to it keeps the region's width the ball's). The disc of its size there.
    const auto px = camera.Project(*predicted);
    if (options_.disc_in_merged && rig_.size() >= 2 && px && expected > 0.0 && background.ready()) {
      const double ratio = options_.max_size_ratio;
      const double disc_area = 0.25 * M_PI * expected * expected;
      const double reach = 0.5 * expected;  // a larger region's box grown by this holds px
      bool larger = false, ball_sized = false;
      for (int k = 0; k < found; ++k) {
        const segment::Region& r = region_of(k);
        if (r.area > ratio * ratio * disc_area || r.major_diameter > ratio * expected) {
          larger = larger || (px->x() >= r.x0 - reach && px->x() <= r.x1 + reach &&
                              px->y() >= r.y0 - reach && px->y() <= r.y1 + reach);
        } else if (SizeFits(r.minor_diameter, expected) &&
                   std::hypot(r.cx - px->x(), r.cy - px->y()) <= expected) {
          ball_sized = true;
        }
      }
      if (larger && !ball_sized) {
        if (auto view = MergedDiscView(c, image, *predicted, *px, expected, covariance)) {
          out->push_back(*view);
          disc_seen = true;
        }
      }
    }
    if (options_.roi_needs_size && !sized) found = 0;
  }
  // Nothing of the ball's size where it is predicted: a faint streak along its predicted path?
  bool streak_seen = false;
  if (found == 0 && !disc_seen && streaks && predicted && velocity && background.ready()) {
    if (auto streak = StreakView(c, image, *predicted, *velocity, covariance)) {
      out->push_back(*streak);
      streak_seen = true;
    }
  }
  if (found == 0) {
    search.fell_back = !search.roi.empty() || (options_.use_roi && predicted.has_value());
    split = false;  // a window searched again on the background: the whole image as usual
    found = both({}, masked);
    if (from_colour && !masked) {
      for (int k = 0; k < found && !ball_coloured_hall_[c]; ++k) {
        ball_coloured_hall_[c] = TooLargeForBall(regions[k], largest);
      }
    }
    // A floor, wall or banner of the ball's colour, the ball maybe joined to it.
    if (splitting && background.ready()) {
      const int n = SplitMerged(c, image, found, largest, measure_only);
      if (n >= 0) {
        found = n;
        split = true;
      }
    }
  }
  // No track, or nothing of it where predicted: the ball may be nowhere sharp, only a faint
  // streak somewhere.
  if ((!predicted || (search.fell_back && !streak_seen && !disc_seen)) && streaks &&
      options_.streaks_anywhere && background.ready()) {
    StreakViews(c, image, out);
  }
  // Every region is looked at (a static spot must stay known however many there are). Regions
  // that were at the same place in the last set (a letter, a lamp; the ball in play moves) come
  // after the others; those static for static_frames sets are dropped; the first
  // candidates_per_camera are kept.
  std::vector<std::pair<bool, int>> order;  // (still, region)
  for (int k = 0; k < found; ++k) {
    const segment::Region& r = region_of(k);
    // A ball, even blurred, is a compact blob: not a wall, not a line.
    if (TooLargeForBall(r, largest) ||
        r.major_diameter > options_.max_elongation * std::max(1.0, r.minor_diameter)) {
      continue;
    }
    const int count = SpotCount(c, {r.cx, r.cy});
    if (count >= options_.static_frames) continue;
    order.emplace_back(count > 1, k);
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  if (static_cast<int>(order.size()) > options_.candidates_per_camera) {
    if ((on_background || masked || crowded) && options_.keep_roundest) {
      // Regions that differ from the background are mostly the players: the roundest are kept
      // (a ball, even blurred over a short exposure, fills the ellipse of its moments; the
      // pieces of players and their clothes that move do not), in the order they came.
      const auto roundness = [&](int k) {
        const segment::Region& r = region_of(k);
        return segment::Roundness(r.area, r.minor_diameter, r.major_diameter);
      };
      std::stable_sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : roundness(a.second) > roundness(b.second);
      });
    }
    order.resize(options_.candidates_per_camera);
    std::sort(order.begin(), order.end());  // (still, region): the order they came in
  }
  for (const auto& [still, k] : order) {
    const segment::Region& r = region_of(k);
    Detection d{c, {r.cx, r.cy}, r.minor_diameter + options_.diameter_bias_px, r.area, false};
    d.still = still;
    d.cut = r.touches_border;
    d.length_px = r.major_diameter;
    if (by_coverage(k)) {
      d.diameter_px = r.diameter;  // the coverage sum: the disc's area, blur or not
      d.by_coverage = true;
    } else if (options_.refine) {
      // The diameter only: the luma-weighted centroid leans to the lit side of the ball,
      // differently in each camera, which the epipolar check does not forgive.
      if (const auto m = segment::MeasureBall(image, r)) {
        // The lens and the encoder blur the ball's edge by a point-spread of psf_sigma_px,
        // which adds psf^2 to the moment the minor diameter comes from: take it out.
        const double psf = options_.psf_sigma_px;
        d.diameter_px =
            std::sqrt(std::max(1.0, m->minor_diameter * m->minor_diameter - 16.0 * psf * psf));
      }
    }
    // A long streak's ends are ramps whose crossings the noise moves: its centroid stays.
    if (options_.edge_centre &&
        r.major_diameter <= options_.edge_max_elongation * std::max(1.0, r.minor_diameter)) {
      // The centre from the ball's edge (ball_edge.h): the region's centroid leans to where the
      // encoder left the ball's chroma and to the lit half.
      const double radius = 0.5 * std::max(r.major_diameter, d.diameter_px) + 0.5;
      if (const auto e = segment::MeasureEdgeCentre(image, r.cx, r.cy, radius, options_.edge);
          e && std::hypot(e->cx - r.cx, e->cy - r.cy) < 0.5 * d.diameter_px + 1.0) {
        d.pixel = {e->cx, e->cy};
        if (EdgeGivesDiameter(*e, options_.edge_diameter_max_elongation)) {
          d.diameter_px = e->minor_diameter;
          d.faint = {e->faint[0], e->faint[1]};
          faint_votes_[c].Add(e->faint);
        } else if (e->minor_diameter > 0.0) {
          // No disc, but its centre leans to the lit side as a disc's would: the width across
          // tells how far (the diameter stays the moments', which the depth and the size
          // checks use; the camera's vote takes only discs).
          d.faint = {e->faint[0], e->faint[1]};
          d.edge_width_px = e->minor_diameter;
        }
      }
    }
    d.observed = d.pixel;
    out->push_back(d);
  }
  if (!window && predicted) {
    for (std::size_t i = first_out; i < out->size(); ++i) {
      const Eigen::Vector2d& p = (*out)[i].observed;
      (*out)[i].outside = stale.empty() || !stale.Contains(p.x(), p.y());
    }
  }
  if (keeps_background()) {
    sized_background();
    background.Update(image, search.roi);
  }
}

FrameSetResult FrameSetTracker::Process(TimeNs t, std::span<const std::optional<ImageView>> images,
                                        std::span<const TimeNs> times) {
  FrameSetResult result;
  result.t = t;
  const int n = rig_.size();
  result.searches.resize(n);
  const TimeNs t0 = clock_ ? clock_() : 0;
  const auto prediction = tracker_.Predict(t);
  const std::optional<Eigen::Vector3d> predicted =
      prediction ? std::optional<Eigen::Vector3d>(prediction->first) : std::nullopt;
  const Eigen::Matrix3d predicted_covariance =
      prediction ? prediction->second : Eigen::Matrix3d::Identity();
  std::vector<std::vector<Detection>> candidates(n);
  const int present = std::min(n, static_cast<int>(images.size()));
  // Each camera's own time (its image's, in the rig's clock) and the ball predicted then.
  const auto image_time = [&](int c) { return c < static_cast<int>(times.size()) ? times[c] : t; };
  std::vector<std::optional<Eigen::Vector3d>> camera_predicted(n, predicted);
  if (predicted) {
    for (int c = 0; c < n; ++c) {
      if (image_time(c) != t) camera_predicted[c] = tracker_.PredictPosition(image_time(c));
    }
  }
  // Each camera's frame period (the shortest interval between its images) and, for the cameras
  // that look for streaks, the velocity predicted at their time.
  std::vector<std::optional<Eigen::Vector3d>> camera_velocity(n);
  std::vector<char> window(n, 1);
  for (int c = 0; c < present; ++c) {
    if (!images[c]) continue;
    const TimeNs at = image_time(c);
    if (last_image_time_[c] && at > *last_image_time_[c]) {
      const double dt = ToSeconds(at - *last_image_time_[c]);
      if (frame_period_s_[c] <= 0.0 || dt < frame_period_s_[c]) frame_period_s_[c] = dt;
    }
    last_image_time_[c] = at;
    // Seconds since the filter last took a measurement (none: no track yet).
    const std::optional<double> since =
        last_taken_t_ ? std::optional<double>(ToSeconds(at - *last_taken_t_)) : std::nullopt;
    // Only one frame on from a measurement: a coasting filter's path may run on through the
    // racket that hit the ball, where an arm's edge can pass for a streak.
    const bool fresh = since && *since <= 1.5 * frame_period_s_[c];
    if (predicted && fresh && SearchesStreaks(c)) {
      camera_velocity[c] = tracker_.PredictVelocity(at);
    }
    window[c] = !since || frame_period_s_[c] <= 0.0 ||
                *since <= (options_.roi_max_missed + 1.5) * frame_period_s_[c];
  }
  const auto search = [&](int c) {
    if (images[c]) {
      SearchCamera(c, *images[c], camera_predicted[c], camera_velocity[c], predicted_covariance,
                   window[c] != 0, &result.searches[c], &candidates[c]);
    }
  };
  if (pool_ && present > 1) {
    pool_->Run(present, search);
  } else {
    for (int c = 0; c < present; ++c) search(c);
  }
  for (int c = 0; c < n; ++c) AgeStaticSpots(c, result.searches[c]);
  MoveToSetTime(t, image_time, result.searches, &candidates);
  const TimeNs t1 = clock_ ? clock_() : 0;
  std::vector<std::pair<int, int>> used;
  std::vector<Hypothesis> hypotheses = Hypotheses(candidates);
  if (options_.whole_fragments && WholeFragments(hypotheses, images, &candidates)) {
    hypotheses = Hypotheses(candidates);
  }
  if (options_.outline_short_views &&
      OutlineShortViews(hypotheses, predicted, images, &candidates)) {
    hypotheses = Hypotheses(candidates);
  }
  const auto in_step = [&](int c) { return image_time(c) == t; };
  if (options_.search_epipolars && n >= 2 &&
      SearchEpipolars(hypotheses, predicted, predicted_covariance, images, in_step, &candidates)) {
    hypotheses = Hypotheses(candidates);
  }
  const bool confirming = options_.confirm_tracks;
  // One camera: each candidate placed by its diameter (nullopt: outside the hall).
  std::vector<std::optional<Measurement>> placed;
  if (n == 1) {
    for (const Detection& d : candidates[0])
      placed.push_back(SphereMeasurement(rig_.cameras[0], d));
  }
  std::optional<Tracklet> confirmed;
  // Detection (camera c, candidate k) is result.detections[offset[c] + k] (flattened below).
  std::vector<int> offset(n + 1, 0);
  for (int c = 0; c < n; ++c) offset[c + 1] = offset[c] + static_cast<int>(candidates[c].size());
  std::vector<int> adopted;  // indices into result.detections of an adopted tracklet's last point
  bool started = false;      // a confirmed tracklet became the track
  if (confirming) {
    // Every distinct candidate of this time-stamp goes to the initiator, best first.
    std::vector<TrackletPoint> points;
    // One camera: every candidate that moved, placed by its diameter (a streak's is the
    // expected one: it says nothing of the depth). A region that stood still since the last set
    // is not one: its depth noise is the same in each (one region, one size), while the
    // initiator takes each point's noise as its own, so that still spots joined by jumps along
    // the ray (near things of other sizes) would fit a flight within one camera's depth noise.
    for (int k = 0; k < static_cast<int>(placed.size()); ++k) {
      const Detection& d = candidates[0][k];
      if (placed[k] && !d.streak && !d.still) points.push_back({t, *placed[k], {k}});
    }
    std::vector<bool> taken_detection(offset[n], false);
    for (const Hypothesis& h : hypotheses) {
      if (h.fragment) continue;  // a new track starts from whole balls
      TrackletPoint p{t, ToMeasurement(h), {}};
      p.still_and_moving = StillAndMoving(h, candidates, p.measurement.position);
      p.streak = true;
      p.off_colour = true;
      for (const auto& [c, k] : h.members) {
        const Detection& d = candidates[c][k];
        p.detections.push_back(offset[c] + k);
        p.streak = p.streak && d.streak && !d.disc;
        p.off_colour =
            p.off_colour && d.streak && d.colour_residual >= options_.off_colour_residual;
      }
      const bool taken = std::any_of(p.detections.begin(), p.detections.end(),
                                     [&](int i) { return taken_detection[i]; });
      const bool repeated = std::any_of(points.begin(), points.end(), [&](const TrackletPoint& q) {
        return std::all_of(p.detections.begin(), p.detections.end(), [&](int i) {
          return std::find(q.detections.begin(), q.detections.end(), i) != q.detections.end();
        });
      });
      if (taken || repeated) continue;
      // A faint streak's size says little: a clutter spot that meets its epipolar line may be
      // paired with it first, so it stays free for the others.
      for (const auto& [c, k] : h.members) {
        if (!candidates[c][k].streak) taken_detection[offset[c] + k] = true;
      }
      points.push_back(std::move(p));
    }
    confirmed = initiator_.Push(t, points);
  }
  if (const Hypothesis* best = Pick(hypotheses, predicted)) {
    result.measurement = ToMeasurement(*best);
    used = best->members;
  }
  // One view places the ball by its diameter in a one-camera rig; with more cameras it only
  // continues a track (a lone view of an orange speck must not start one), at the predicted depth.
  std::optional<WaitingView> waits;
  if (!result.measurement && options_.single_camera_fallback) {
    std::vector<double> motion_px(n, std::numeric_limits<double>::quiet_NaN());
    if (predicted) {
      if (const auto velocity = tracker_.PredictVelocity(t)) {
        motion_px = PredictedMotion(*predicted, *velocity);
      }
    }
    if (n == 1) {
      result.measurement =
          SingleView(candidates[0], placed, predicted, predicted_covariance, motion_px, &used);
    } else if (predicted) {
      if (auto lone = NearestLoneView(candidates, *predicted, predicted_covariance, motion_px)) {
        // A lone view whose depth the filter knows is a row at once; with the rows held
        // (confirming), every lone view waits for the fixes after it (PlaceLoneViews): from
        // the past alone its depth is an extrapolation.
        const bool firm = lone->depth_sigma <= options_.single_view_max_depth_sigma;
        const bool held = confirming && options_.lone_view_depth_sigma > 0.0;
        if (held && lone->depth_sigma <= std::max(options_.lone_view_depth_sigma,
                                                  options_.single_view_max_depth_sigma)) {
          const auto [c, k] = lone->id;
          waits = WaitingView{t, c, candidates[c][k].pixel, lone->ray, offset[c] + k};
        }
        if (waits || (firm && !held)) {
          result.measurement = lone->measurement;
          used = {lone->id};
        }
      }
    }
  }
  const TimeNs t2 = clock_ ? clock_() : 0;
  // With confirmation a track starts only from the initiator (below), never from this step.
  // A coasting track of 2+ cameras takes nothing from outside its windows (Detection::outside),
  // nor anything while it coasts past the table's end (CoastsPastEnd: the ball may have been
  // hit): what the images show goes to the initiator, which replaces the track once it confirms
  // a flight. (One camera's views are judged again by the smoother, and its initiator confirms
  // late: there the track takes them; docs/DECISIONS.md.)
  const bool outside = n > 1 && (std::any_of(used.begin(), used.end(),
                                             [&](const std::pair<int, int>& v) {
                                               return candidates[v.first][v.second].outside;
                                             }) ||
                                 CoastsPastEnd(t, predicted));
  const bool was_tracking = tracker_.tracking();
  if (!confirming || tracker_.tracking()) {
    result.state = tracker_.Step(t, outside ? std::optional<Measurement>() : result.measurement);
  }
  // The track ended here because it does not fall as a ball can: its rows were not the ball, nor
  // its last points (kept before a flight adopted below replaces the filter).
  const bool not_ball = was_tracking && !tracker_.tracking() && tracker_.ended_not_falling();
  const std::vector<FallPoint> not_ball_points =
      not_ball ? tracker_.recent() : std::vector<FallPoint>{};
  if (confirming) {
    const bool took = result.state && result.state->measured;
    // A confirmed tracklet replaces a track that did not take this time-stamp's measurement, or
    // did not take the tracklet's earlier points (the ball was hit and the filter coasted, then
    // its grown gate let the ball in again; or the track had followed something else): the
    // filter replayed from the tracklet knows the new flight, and its points become rows.
    const bool missed_points =
        confirmed && confirmed->points.size() >= 2 &&
        (!last_taken_t_ || confirmed->points[confirmed->points.size() - 2].t > *last_taken_t_);
    const bool adopt = confirmed && (!took || missed_points);
    if (adopt) {
      used.clear();
      AdoptTracklet(*confirmed, &result);
      adopted = confirmed->points.back().detections;
      started = true;
    } else if (!took) {
      result.tentative = result.measurement.has_value();
      used.clear();
    } else if (waits) {
      // The filter took a lone view whose depth it does not know yet: the row waits.
      result.tentative = true;
      used.clear();
      waiting_.push_back(*waits);
    }
    // The track follows the tracklet's flight already: the points of it the filter refused (the
    // first after a hit, before the coasting filter's gate grew) are rows all the same.
    if (confirmed && !adopt && n >= 2) ReviseRefused(*confirmed, &result);
  }
  if (started && n >= 2) {
    BackFill(tracker_.history(), confirmed->points[confirmed->flight_start].t, &result);
    FillGaps(tracker_.history(), confirmed->points[confirmed->flight_start].t, &result);
  }
  const TimeNs hold = FromSeconds(options_.initiator.max_span_s);
  while (!taken_.empty() && t - taken_.front() > hold) taken_.pop_front();
  NoteTaken(t, result.revisions);
  // A track that ended, or that a confirmed flight replaced, after predictions past its last
  // measurement: those rows were a path no view confirmed (the flight before a hit carried on
  // through the racket, or past the recording's end): dropped, but for the time-stamps the new
  // flight's revisions took.
  if (confirming && n >= 2 && (started || (was_tracking && !tracker_.tracking()))) {
    DropCoasted(&result);
  }
  if (result.state && !result.state->measured && tracker_.tracking() && !started) {
    coasted_.push_back(t);
  }
  if (result.state && result.state->measured) {
    coasted_.clear();
    taken_.push_back(t);
    last_taken_t_ = t;
    if (!result.tentative && result.measurement && result.measurement->cameras >= 2) {
      fixes_.push_back(t);
    }
  }
  for (const auto& [c, k] : used) candidates[c][k].accepted = true;
  for (auto& list : candidates) {
    for (auto& d : list) result.detections.push_back(d);
  }
  for (int i : adopted) result.detections[i].accepted = true;
  PlaceLoneViews(&result);
  if (confirming) TakeBackRows(t, not_ball, started, &result);
  // What the track followed goes on in the initiator's tracklets: not confirmed again until
  // judged falling.
  if (not_ball) initiator_.NotTheBall(not_ball_points, options_.initiator.gate);
  while (!past_.empty() && t - past_.front().t > hold) past_.pop_front();
  const bool row = result.state && result.state->measured && !result.tentative;
  Vector6d row_state = Vector6d::Zero();
  if (row) row_state << result.state->position, result.state->velocity;
  past_.push_back({t, result.detections, row, row_state});
  if (clock_) {
    const TimeNs t3 = clock_();
    result.stages = {t1 - t0, t2 - t1, t3 - t2};
  }
  return result;
}

void FrameSetTracker::MoveToSetTime(TimeNs t, const std::function<TimeNs(int)>& image_time,
                                    const std::vector<CameraSearch>& searches,
                                    std::vector<std::vector<Detection>>* candidates) {
  last_views_.resize(candidates->size());
  for (int c = 0; c < static_cast<int>(candidates->size()); ++c) {
    std::vector<Detection>& views = (*candidates)[c];
    LastViews& last = last_views_[c];
    const CameraClock& clock = rig_.cameras[c].clock;
    LastViews now;
    for (Detection& d : views) {
      const TimeNs when = image_time(c) + FromSeconds(clock.RowDelay(d.observed.y()));
      now.pixels.push_back(d.observed);
      now.times.push_back(when);
      if (when == t) continue;
      // The same thing in the last image: the nearest view within the ball's reach.
      int nearest = -1;
      double best = 0.0;
      for (int k = 0; k < static_cast<int>(last.pixels.size()); ++k) {
        const double dt = ToSeconds(when - last.times[k]);
        const double d2 = (d.observed - last.pixels[k]).squaredNorm();
        if (dt > 0.0 && dt <= options_.motion_max_gap_s &&
            d2 <= std::pow(options_.motion_max_px_s * dt, 2) && (nearest < 0 || d2 < best)) {
          nearest = k, best = d2;
        }
      }
      if (nearest < 0) continue;
      const Eigen::Vector2d velocity =
          (d.observed - last.pixels[nearest]) / ToSeconds(when - last.times[nearest]);
      d.pixel -= velocity * ToSeconds(when - t);
    }
    if (searches[c].present) last = std::move(now);
  }
}

void FrameSetTracker::AdoptTracklet(const Tracklet& tracklet, FrameSetResult* result) {
  const auto& points = tracklet.points;
  // The flight before a contact the tracklet's gate took the ball through (a hit; a bounce the
  // filter would have followed too): its points the track did not take become rows of a filter
  // of their own. Not with one camera: its points, placed by their diameters, are known along
  // their rays to centimetres, and where its flights part is the smoother's to say (mono tuning
  // 4: 82 -> 68 % recall).
  const std::size_t start = rig_.size() >= 2 ? tracklet.flight_start : 0;
  std::size_t first = 0;
  while (first < start && last_taken_t_ && points[first].t <= *last_taken_t_) ++first;
  const auto all = [](TimeNs) { return true; };
  if (start >= first + 2) {
    BallTracker before(tracker_options_);
    ReplayPoints(tracklet, first, start, &before, all, result);
  }
  // The flight it ends with: the filter replays it; all but its last point are revisions.
  tracker_ = BallTracker(tracker_options_);
  ReplayPoints(tracklet, start, points.size() - 1, &tracker_, all, result);
  const std::optional<TrackedState> last =
      tracker_.Step(points.back().t, points.back().measurement);
  result->state = last;
  result->measurement = tracklet.points.back().measurement;
  result->tentative = false;
  result->new_track = true;
}

const FrameSetTracker::PastSet* FrameSetTracker::FreeSetsBefore(
    TimeNs flight_t0, const FrameSetResult& result, std::vector<const PastSet*>* between) const {
  const TimeNs hold = FromSeconds(options_.initiator.max_span_s);
  // The newest set before the flight: it must be a measured row within the hold, and every set
  // between it and the flight unmeasured and free (no row, no revision, not taken).
  between->clear();
  for (auto set = past_.rbegin(); set != past_.rend(); ++set) {
    if (set->t >= flight_t0) continue;
    if (result.t - set->t > hold) return nullptr;
    if (set->measured) return &*set;
    if (RowMadeSince(*set, result)) return nullptr;
    between->push_back(&*set);
  }
  return nullptr;
}

bool FrameSetTracker::BetweenContacts(const SmoothedState& first_step, TimeNs flight_t0,
                                      FrameSetResult* result) {
  std::vector<const PastSet*> between;
  const PastSet* anchor = FreeSetsBefore(flight_t0, *result, &between);
  if (!anchor || between.size() < 2 ||
      ToSeconds(flight_t0 - anchor->t) > options_.contact_flight_max_s) {
    return false;
  }
  const KalmanOptions& kalman = tracker_options_.kalman;
  // Each set's points of two views of the ball's size (as between[]: newest first).
  std::vector<std::vector<Eigen::Vector3d>> points(between.size());
  for (std::size_t s = 0; s < between.size(); ++s) {
    const auto& d = between[s]->detections;
    for (std::size_t i = 0; i < d.size(); ++i) {
      for (std::size_t j = i + 1; j < d.size(); ++j) {
        if (d[i].camera == d[j].camera || d[i].still || d[j].still || d[i].cut || d[j].cut) {
          continue;
        }
        const Camera& a = rig_.cameras[d[i].camera];
        const Camera& b = rig_.cameras[d[j].camera];
        if (EpipolarDistance(a, d[i].pixel, b, d[j].pixel) > options_.epipolar_px) continue;
        const std::vector<Observation> pair = {{d[i].camera, d[i].pixel},
                                               {d[j].camera, d[j].pixel}};
        const auto e = TriangulateObservations(rig_.cameras, pair, triangulation_);
        if (!e || e->mean_reprojection_px > options_.reprojection_px) continue;
        const double expected_a = ExpectedDiameterPx(a, e->point);
        const double expected_b = ExpectedDiameterPx(b, e->point);
        if (!ViewSizeFits(d[i].diameter_px, expected_a) ||
            !ViewSizeFits(d[j].diameter_px, expected_b) || Fragment(d[i].diameter_px, expected_a) ||
            Fragment(d[j].diameter_px, expected_b)) {
          continue;
        }
        points[s].push_back(e->point);
      }
    }
  }
  const TimeNs step = FromSeconds(0.0005);
  const Eigen::Vector3d g(0.0, 0.0, -kalman.gravity);
  double best = options_.contact_max_m;
  std::optional<std::pair<Vector6d, TimeNs>> flight;
  // Each two sets in a row, the older first.
  for (std::size_t k = between.size() - 1; k >= 1; --k) {
    const PastSet& older = *between[k];
    const PastSet& newer = *between[k - 1];
    const double dt = ToSeconds(newer.t - older.t);
    for (const Eigen::Vector3d& pa : points[k]) {
      for (const Eigen::Vector3d& pb : points[k - 1]) {
        Vector6d x;
        x << pa, (pb - pa) / dt - 0.5 * g * dt;  // the velocity at the older set
        if (x.tail<3>().norm() > options_.initiator.max_speed) continue;
        const Meeting with_before =
            FlightsMeet(kalman, anchor->state, anchor->t, x, older.t, anchor->t, older.t, step);
        const Meeting with_new = FlightsMeet(kalman, x, older.t, first_step.state, first_step.t,
                                             newer.t, first_step.t, step);
        const double worst = std::max(with_before.distance, with_new.distance);
        if (worst <= best && with_before.dv.norm() > options_.backfill_contact_mps &&
            with_new.dv.norm() > options_.backfill_contact_mps) {
          best = worst;
          flight = std::make_pair(x, older.t);
        }
      }
    }
  }
  if (!flight) return false;
  const double sigma = kFlightSigmaFloor;
  for (const PastSet* set : between) {
    Vector6d x = flight->first;
    CarryFlight(kalman, ToSeconds(set->t - flight->second), &x);
    Revision r;
    if (RowOnFlight(*set, x, sigma * sigma * Eigen::Matrix3d::Identity(), &r)) {
      r.state.between_contacts = true;
      PushRevision(std::move(r), result);
    }
  }
  return true;
}

bool FrameSetTracker::Bridge(std::span<const FilterStep> steps,
                             std::span<const SmoothedState> smoothed, std::size_t first,
                             TimeNs flight_t0, FrameSetResult* result) {
  std::vector<const PastSet*> between;
  const PastSet* anchor = FreeSetsBefore(flight_t0, *result, &between);
  if (!anchor || between.empty()) return false;
  // The anchor's point, from the views its row took.
  std::vector<Observation> o;
  for (const Detection& d : anchor->detections) {
    if (d.accepted) o.push_back({d.camera, d.pixel});
  }
  if (o.size() < 2) return false;
  const auto a = TriangulateObservations(rig_.cameras, o, triangulation_);
  if (!a || a->mean_reprojection_px > options_.reprojection_px) return false;
  // One flight with a constant acceleration through the anchor and the new flight's first
  // bridge_span_s (its smoothed states): x(t) = A + v tau + a tau^2 / 2, tau = t - t_anchor.
  std::vector<std::pair<double, Eigen::Vector3d>> points;
  for (std::size_t i = first; i < steps.size(); ++i) {
    if (ToSeconds(steps[i].t - steps[first].t) > options_.bridge_span_s) break;
    points.emplace_back(ToSeconds(steps[i].t - anchor->t), smoothed[i].state.head<3>());
  }
  if (points.size() < 3) return false;
  Eigen::MatrixXd m(points.size(), 2);
  Eigen::MatrixXd rhs(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double tau = points[i].first;
    m.row(static_cast<Eigen::Index>(i)) << tau, 0.5 * tau * tau;
    rhs.row(static_cast<Eigen::Index>(i)) = (points[i].second - a->point).transpose();
  }
  const Eigen::MatrixXd va = m.colPivHouseholderQr().solve(rhs);  // rows: v, a
  const Eigen::Vector3d v0 = va.row(0).transpose(), acc = va.row(1).transpose();
  // The bridge's position and velocity tau after the anchor.
  const auto on_bridge = [&](double tau) {
    Vector6d x;
    x << a->point + v0 * tau + 0.5 * acc * tau * tau, v0 + acc * tau;
    return x;
  };
  double rms = 0.0;
  for (const auto& [tau, p] : points) rms += (on_bridge(tau).head<3>() - p).squaredNorm();
  rms = std::sqrt(rms / static_cast<double>(points.size()));
  // A ball's acceleration: gravity, and what the air gives it (drag, Magnus of max_spin).
  const double speed = on_bridge(0.5 * points.front().first).tail<3>().norm();
  const double most =
      MostAirAcceleration(speed, tracker_options_.fall, tracker_options_.kalman.drag_per_mass);
  const Eigen::Vector3d g(0.0, 0.0, -tracker_options_.kalman.gravity);
  if (rms > options_.bridge_max_rms || (acc - g).norm() > most + 2.0) return false;
  // Each set between: its views within backfill_px of the bridge there; one view placed on its
  // ray where the bridge crosses it.
  const double sigma = std::max(rms, kFlightSigmaFloor);
  for (const PastSet* set : between) {
    Revision r;
    if (RowOnFlight(*set, on_bridge(ToSeconds(set->t - anchor->t)),
                    sigma * sigma * Eigen::Matrix3d::Identity(), &r)) {
      PushRevision(std::move(r), result);
    }
  }
  return true;
}

void FrameSetTracker::BackFill(std::span<const FilterStep> steps, TimeNs flight_t0,
                               FrameSetResult* result) {
  if (!(options_.backfill_px > 0.0) || steps.empty() || past_.empty()) return;
  const TimeNs hold = FromSeconds(options_.initiator.max_span_s);
  // A row measured then, or made one since (a lone view placed, this adoption's flight before
  // the hit, an earlier back-fill): the flight before. Not a lone view still waiting for its
  // depth (PlaceLoneViews): the coasting track's guess after a hit, which the flight replaces.
  const auto ends_search = [&](const PastSet& set) {
    return result->t - set.t > hold || set.measured || RowMadeSince(set, *result);
  };
  const auto before = std::find_if(past_.rbegin(), past_.rend(),
                                   [&](const PastSet& set) { return set.t < flight_t0; });
  if (before == past_.rend() || ends_search(*before)) return;  // nothing to fill: not smoothed
  // The track's first step (its flight's first point), smoothed with the steps after it.
  std::size_t first = steps.size() - 1;
  while (first > 0 && !steps[first].start) --first;
  const std::vector<SmoothedState> smoothed_steps = SmoothSteps(steps);
  const SmoothedState& s0 = smoothed_steps[first];
  if (options_.bridge_span_s > 0.0 && Bridge(steps, smoothed_steps, first, flight_t0, result)) {
    return;
  }
  if (options_.contact_max_m > 0.0 && BetweenContacts(s0, flight_t0, result)) return;
  const KalmanOptions& kalman = tracker_options_.kalman;
  // The flight carried back set by set (x, p: a backward filter). Each set of two views or more
  // that it takes corrects it, so a set further back is judged by the sets already taken, not
  // by the first state alone (a toss started from three points knows its depth 1-2 frames back
  // only to ~5 cm; after the sets before it, to millimetres).
  Vector6d x = s0.state;
  Matrix6d p = s0.covariance;
  KalmanOptions measured = kalman;
  measured.noise = KalmanOptions::Noise::kAcceleration;  // the points' own covariances
  KalmanFilter backward(measured);
  TimeNs at = s0.t;
  // A view's centre moved back from its faint side by the width it lost against the ball's at
  // the carried flight's point (as the hypotheses' and lone views').
  const auto shaded = [&](const Detection& d) {
    return ShadedCentre(d, ExpectedDiameterPx(rig_.cameras[d.camera], x.head<3>()));
  };
  int missed = 0;  // sets in a row with no view of the flight
  // Single views whose depth the flight did not know to single_view_max_depth_sigma, newest
  // first: placed when a set of two views further back fixes the flight, else given up.
  std::vector<Revision> pending;
  const auto push = [&](Revision r) { PushRevision(std::move(r), result); };
  // Single views placed since the last set of two views (none before them fixed the flight):
  // rows unless the search ends at a contact after them (backfill_contact_mps).
  std::vector<Revision> placed;
  const auto push_placed = [&] {
    for (Revision& r : placed) push(std::move(r));
    placed.clear();
  };
  // The search ends at `set`: a measured row whose views are not on the flight (x, p at `at`).
  // Its flight carried forward and the new one meet at the contact; the views placed before it
  // are dropped.
  const auto ends_at_other_flight = [&](const PastSet& set) {
    if (!(options_.backfill_contact_mps > 0.0) || !set.measured || placed.empty()) return;
    // (Up to the flight's first point, not at it.)
    const Meeting contact =
        FlightsMeet(kalman, set.state, set.t, x, at, set.t, flight_t0 - 1, FromSeconds(0.001));
    if (contact.dv.norm() <= options_.backfill_contact_mps) return;
    std::erase_if(placed, [&](const Revision& r) { return r.t < contact.t; });
  };
  // Whether two views of `set` the track took lie on the flight there.
  const auto on_flight = [&](const PastSet& set) {
    Vector6d y = x;
    CarryFlight(kalman, ToSeconds(set.t - at), &y);
    return TakenViewsOn(set, y.head<3>()).size() >= 2;
  };
  // The single views since the flight's last fix (x, p at `at`), whose depth the flight from
  // after them did not know: carried from this fix, which knows the velocity over the whole
  // span between.
  const auto place_pending = [&] {
    for (Revision& v : pending) {
      Vector6d y = x;
      Matrix6d c = p;
      CarryFlight(kalman, ToSeconds(v.t - at), &y, &c);
      if (PlaceOnRay(y, c.topLeftCorner<3, 3>(), &v)) push(std::move(v));
    }
    pending.clear();
  };
  for (auto set = past_.rbegin(); set != past_.rend(); ++set) {
    if (set->t >= flight_t0) continue;  // the flight's own sets: the adoption's revisions
    const bool ends = ends_search(*set);
    if (ends && !(set->measured && !pending.empty())) {
      if (!on_flight(*set)) ends_at_other_flight(*set);
      break;
    }
    CarryFlight(kalman, ToSeconds(set->t - at), &x, &p);
    at = set->t;
    // A row measured then ends the search; if its views lie on the flight (backfill_px), its
    // point fixes the flight for the single views after it that wait, and is the row (a track
    // that took it through its grown gate after a hit wrote its prior's pull too).
    if (ends) {
      Revision r;
      r.t = set->t;
      std::vector<Observation> o;
      Hypothesis views;
      for (const int i : TakenViewsOn(*set, x.head<3>())) {
        const Detection& d = set->detections[i];
        o.push_back({d.camera, shaded(d)});
        views.members.emplace_back(d.camera, i);
        r.accepted.push_back(i);
      }
      if (o.size() >= 2) {
        if (const auto e = TriangulateObservations(rig_.cameras, o, triangulation_);
            e && e->mean_reprojection_px <= options_.reprojection_px) {
          views.estimate = *e;
          r.measurement = ToMeasurement(views);
          backward.Reset(x, p);
          backward.Update(r.measurement.position, r.measurement.covariance);
          x = backward.state();
          p = backward.covariance();
          place_pending();
          push_placed();
          r.state.velocity = x.tail<3>();
          push(std::move(r));
        }
      }
      ends_at_other_flight(*set);  // (nothing placed is left after a fix)
      break;
    }
    Revision r;
    r.t = set->t;
    std::vector<Observation> observations;
    Hypothesis views;
    ViewsOnFlight(*set, x.head<3>(), &r, &observations, &views);
    if (observations.empty()) {
      if (++missed > options_.backfill_max_missed) break;
      continue;
    }
    missed = 0;
    backward.Reset(x, p);
    if (observations.size() >= 2) {
      // Two views or more: the flight only tells which; the point is theirs.
      const auto estimate = TriangulateObservations(rig_.cameras, observations, triangulation_);
      if (!estimate || estimate->mean_reprojection_px > options_.reprojection_px) break;
      views.estimate = *estimate;
      r.measurement = ToMeasurement(views);
      // The flight corrected by the point (the filter's update, with the point's covariance).
      backward.Update(r.measurement.position, r.measurement.covariance);
      x = backward.state();
      p = backward.covariance();
      place_pending();
      push_placed();
      push(std::move(r));
    } else {
      // One: its ray corrects the flight across it; its depth is the flight's, if it knows it
      // (else it waits for a fix further back).
      const Detection& d = set->detections[r.accepted.front()];
      const Camera& camera = rig_.cameras[d.camera];
      const Eigen::Vector3d ray = camera.RayDirection(shaded(d));
      const double depth = std::max(0.1, (x.head<3>() - camera.Center()).dot(ray));
      const double across = depth * options_.pixel_sigma / camera.fx;
      const double along = options_.single_view_depth_sigma;
      backward.Update(camera.Center() + depth * ray,
                      along * along * ray * ray.transpose() +
                          across * across * (Eigen::Matrix3d::Identity() - ray * ray.transpose()));
      x = backward.state();
      p = backward.covariance();
      r.measurement.cameras = 1;
      r.state.velocity = x.tail<3>();
      if (PlaceOnRay(x, p.topLeftCorner<3, 3>(), &r)) {
        placed.push_back(std::move(r));
      } else {
        pending.push_back(std::move(r));
      }
    }
  }
  push_placed();
}

void FrameSetTracker::FillGaps(std::span<const FilterStep> steps, TimeNs flight_t0,
                               FrameSetResult* result) {
  // (The held sets inside the flight whose best candidate was no whole pair, e.g. one camera's
  // view a 3 px cap of a shaded ball: the smoothed flight on both sides tells which views are
  // the ball, as BackFill's carried flight does before it.)
  if (!(options_.backfill_px > 0.0) || steps.empty() || past_.empty()) return;
  std::size_t first = steps.size() - 1;
  while (first > 0 && !steps[first].start) --first;
  const std::vector<SmoothedState> smoothed = SmoothSteps(steps);
  for (const PastSet& set : past_) {
    // Inside the flight: after its first point, before the track's last step.
    if (set.t <= flight_t0 || set.t >= steps.back().t) continue;
    if (set.measured || Taken(set.t) ||
        std::any_of(result->revisions.begin(), result->revisions.end(),
                    [&](const Revision& r) { return r.t == set.t; })) {
      continue;
    }
    // The smoothed flight at the step nearest the set, carried to it.
    std::size_t k = first;
    for (std::size_t i = first; i < steps.size(); ++i) {
      if (std::abs(ToSeconds(steps[i].t - set.t)) < std::abs(ToSeconds(steps[k].t - set.t))) k = i;
    }
    Vector6d x = smoothed[k].state;
    Matrix6d p = smoothed[k].covariance;
    CarryFlight(tracker_options_.kalman, ToSeconds(set.t - steps[k].t), &x, &p);
    Revision r;
    if (RowOnFlight(set, x, p.topLeftCorner<3, 3>(), &r)) PushRevision(std::move(r), result);
  }
}

bool FrameSetTracker::RowOnFlight(const PastSet& set, const Vector6d& flight,
                                  const Eigen::Matrix3d& covariance, Revision* r) const {
  r->t = set.t;
  std::vector<Observation> observations;
  Hypothesis views;
  ViewsOnFlight(set, flight.head<3>(), r, &observations, &views);
  if (observations.empty()) return false;
  if (observations.size() == 1) return PlaceOnRay(flight, covariance, r);
  const auto estimate = TriangulateObservations(rig_.cameras, observations, triangulation_);
  if (!estimate || estimate->mean_reprojection_px > options_.reprojection_px) return false;
  views.estimate = *estimate;
  r->measurement = ToMeasurement(views);
  r->state.velocity = flight.tail<3>();
  return true;
}

std::vector<int> FrameSetTracker::TakenViewsOn(const PastSet& set,
                                               const Eigen::Vector3d& point) const {
  std::vector<int> on;
  for (int i = 0; i < static_cast<int>(set.detections.size()); ++i) {
    const Detection& d = set.detections[i];
    const auto seen = rig_.cameras[d.camera].Project(point);
    if (d.accepted && seen && (*seen - d.pixel).norm() <= options_.backfill_px) on.push_back(i);
  }
  return on;
}

void FrameSetTracker::ViewsOnFlight(const PastSet& set, const Eigen::Vector3d& point, Revision* r,
                                    std::vector<Observation>* observations,
                                    Hypothesis* views) const {
  std::vector<int> nearest(rig_.size(), -1);
  std::vector<double> nearest_px(rig_.size(), options_.backfill_px);
  for (int i = 0; i < static_cast<int>(set.detections.size()); ++i) {
    const Detection& d = set.detections[i];
    if (d.still || d.cut) continue;
    const Camera& camera = rig_.cameras[d.camera];
    const auto seen = camera.Project(point);
    if (!seen) continue;
    // No fragment (a highlight, the lit part of a shaded ball): its centre is off the ball's.
    // (A region merged with a hand of the ball's colour about it is taken: the flight tells
    // which view, earlier sets of two views measure it, as a new track's first ones.)
    if (!d.streak && Fragment(d.diameter_px, ExpectedDiameterPx(camera, point))) continue;
    const double off = (*seen - d.pixel).norm();
    if (off <= nearest_px[d.camera]) nearest[d.camera] = i, nearest_px[d.camera] = off;
  }
  for (int c = 0; c < rig_.size(); ++c) {
    if (nearest[c] < 0) continue;
    const Detection& d = set.detections[nearest[c]];
    r->accepted.push_back(nearest[c]);
    // (The view's centre moved back from its faint side by the width it lost against the
    // ball's at the flight's point, as the hypotheses' and lone views'.)
    observations->push_back({c, ShadedCentre(d, ExpectedDiameterPx(rig_.cameras[c], point))});
    views->members.emplace_back(c, nearest[c]);
  }
}

void FrameSetTracker::PushRevision(Revision r, FrameSetResult* result) {
  r.state.t = r.t;
  r.state.position = r.measurement.position;
  r.state.measured = true;
  r.state.cameras = r.measurement.cameras;
  // A view it takes is no longer a waiting lone view.
  std::erase_if(waiting_, [&](const WaitingView& w) { return w.t == r.t; });
  result->revisions.push_back(std::move(r));
}

bool FrameSetTracker::PlaceOnRay(const Vector6d& flight, const Eigen::Matrix3d& covariance,
                                 Revision* r) const {
  const PastSet* set = nullptr;
  for (const PastSet& s : past_) {
    if (s.t == r->t) set = &s;
  }
  if (!set || r->accepted.size() != 1) return false;
  const Detection& d = set->detections[r->accepted.front()];
  const Camera& camera = rig_.cameras[d.camera];
  // (The view's centre moved back from its faint side, as the hypotheses' and lone views'.)
  const Eigen::Vector3d ray =
      camera.RayDirection(ShadedCentre(d, ExpectedDiameterPx(camera, flight.head<3>())));
  if (std::sqrt(ray.dot(covariance * ray)) > options_.single_view_max_depth_sigma) return false;
  const double depth = (flight.head<3>() - camera.Center()).dot(ray);
  r->measurement.position = camera.Center() + depth * ray;
  r->measurement.covariance = covariance;
  r->measurement.cameras = 1;
  r->state.velocity = flight.tail<3>();
  return true;
}

bool FrameSetTracker::Waiting(TimeNs t) const {
  return std::any_of(waiting_.begin(), waiting_.end(),
                     [&](const WaitingView& w) { return w.t == t; });
}

void FrameSetTracker::ReviseRefused(const Tracklet& tracklet, FrameSetResult* result) {
  const BallTracker replay = ReviseUntaken(tracklet, tracklet.points.size() - 1, result);
  // The track took the flight's points through its grown gate after it coasted (a hit the
  // hitter hid from a camera): the sets before the flight's first point are looked at as for a
  // new track.
  if (rig_.size() >= 2) {
    BackFill(replay.history(), tracklet.points[tracklet.flight_start].t, result);
    FillGaps(replay.history(), tracklet.points[tracklet.flight_start].t, result);
  }
}

BallTracker FrameSetTracker::ReviseUntaken(const Tracklet& tracklet, std::size_t end,
                                           FrameSetResult* result) const {
  BallTracker replay(tracker_options_);
  ReplayPoints(
      tracklet, tracklet.flight_start, end, &replay, [&](TimeNs t) { return !Taken(t); }, result);
  return replay;
}

void FrameSetTracker::TakeBackRows(TimeNs t, bool not_ball, bool started, FrameSetResult* result) {
  const TimeNs hold = FromSeconds(RowHoldSeconds(options_));
  while (!track_rows_.empty() && t - track_rows_.front() > hold) track_rows_.pop_front();
  if (not_ball) {
    // Before the revisions of a flight adopted at t (oldest first, as ResultHold applies them).
    std::vector<Revision> back;
    for (const TimeNs row : track_rows_) {
      Revision r;
      r.t = row;
      r.not_ball = true;
      back.push_back(std::move(r));
    }
    result->revisions.insert(result->revisions.begin(), back.begin(), back.end());
    taken_back_ += static_cast<int>(back.size());
  }
  if (not_ball || started) track_rows_.clear();
  const auto note = [&](TimeNs row) {
    const auto at = std::lower_bound(track_rows_.begin(), track_rows_.end(), row);
    if (at == track_rows_.end() || *at != row) track_rows_.insert(at, row);
  };
  for (const Revision& r : result->revisions) {
    if (!r.drop && !r.not_ball && r.state.measured && t - r.t <= hold) note(r.t);
  }
  if (result->state && result->state->measured && !result->tentative) note(t);
}

bool FrameSetTracker::RowMadeSince(const PastSet& set, const FrameSetResult& result) const {
  return (Taken(set.t) && !Waiting(set.t)) ||
         std::any_of(result.revisions.begin(), result.revisions.end(),
                     [&](const Revision& r) { return r.t == set.t; });
}

bool FrameSetTracker::Taken(TimeNs t) const {
  return std::find(taken_.begin(), taken_.end(), t) != taken_.end();
}

void FrameSetTracker::NoteTaken(TimeNs now, const std::vector<Revision>& revisions) {
  const TimeNs hold = FromSeconds(options_.initiator.max_span_s);
  for (const Revision& r : revisions) {
    if (now - r.t <= hold && !Taken(r.t)) {
      taken_.insert(std::upper_bound(taken_.begin(), taken_.end(), r.t), r.t);
    }
  }
}

std::vector<Revision> FrameSetTracker::Finish() {
  if (rig_.size() < 2 || !options_.confirm_tracks || past_.empty()) return {};
  if (last_taken_t_ && *last_taken_t_ == past_.back().t) return {};
  FrameSetResult result;
  if (const std::optional<Tracklet> flight = initiator_.Finish()) {
    ReviseUntaken(*flight, flight->points.size(), &result);
    NoteTaken(past_.back().t, result.revisions);
  }
  // The recording ended while the track coasted: its predictions past the last measurement go.
  DropCoasted(&result);
  return std::move(result.revisions);
}

void FrameSetTracker::DropCoasted(FrameSetResult* result) {
  std::vector<Revision> drops;
  for (const TimeNs c : coasted_) {
    if (Taken(c)) continue;
    Revision r;
    r.t = c;
    r.drop = true;
    drops.push_back(std::move(r));
  }
  coasted_.clear();
  // Oldest first, before the revisions that give time-stamps a measured state.
  result->revisions.insert(result->revisions.begin(), drops.begin(), drops.end());
}

int FrameSetTracker::SpotAt(int camera, const Eigen::Vector2d& pixel) const {
  const auto& spots = static_spots_[camera];
  for (int i = 0; i < static_cast<int>(spots.size()); ++i) {
    if ((spots[i].pixel - pixel).norm() <= options_.static_px) return i;
  }
  return -1;
}

bool FrameSetTracker::IsStaticSpot(int camera, const Eigen::Vector2d& pixel) const {
  const int i = SpotAt(camera, pixel);
  if (i < 0) return false;
  const StaticSpot& spot = static_spots_[camera][i];
  return spot.count + (spot.seen ? 0 : 1) >= options_.static_frames;
}

int FrameSetTracker::SpotCount(int camera, const Eigen::Vector2d& pixel) {
  const int i = SpotAt(camera, pixel);
  if (i < 0) {
    static_spots_[camera].push_back({pixel, 1, true});
    return 1;
  }
  StaticSpot& spot = static_spots_[camera][i];
  if (!spot.seen) ++spot.count;
  spot.seen = true;
  return spot.count;
}

void FrameSetTracker::AgeStaticSpots(int camera, const CameraSearch& search) {
  auto& spots = static_spots_[camera];
  // Only where the camera looked: a lamp outside the window is not gone.
  const bool whole = search.roi.empty() || search.fell_back;
  for (StaticSpot& spot : spots) {
    const bool looked =
        search.present && (whole || search.roi.Contains(spot.pixel.x(), spot.pixel.y()));
    if (!spot.seen && looked) spot.count -= 3;  // gone for a moment: forgotten fast
    spot.seen = false;
  }
  std::erase_if(spots, [](const StaticSpot& s) { return s.count <= 0; });
}

Eigen::Vector2d FrameSetTracker::FaintSide(const Detection& view) const {
  Eigen::Vector2d faint = view.faint;
  if (faint.isZero() && !view.streak && !view.by_coverage) {
    faint_votes_[view.camera].Agreed(options_.shade, faint.data());
  }
  return faint;
}

Eigen::Vector2d FrameSetTracker::ShadedCentre(const Detection& view, double expected_px) const {
  Eigen::Vector2d centre = view.pixel;
  if (!options_.shade_correction || view.outlined) return centre;
  const Eigen::Vector2d faint = FaintSide(view);
  const double width = view.edge_width_px > 0.0 ? view.edge_width_px : view.diameter_px;
  segment::UnshadeCentre(width, faint.data(), expected_px, options_.shade, &centre.x(),
                         &centre.y());
  return centre;
}

bool FrameSetTracker::CoastsPastEnd(TimeNs t,
                                    const std::optional<Eigen::Vector3d>& predicted) const {
  if (!options_.past_end_takes_nothing || !predicted || !last_taken_t_) return false;
  // The slowest camera's frame: a set missed is one of its frames gone by.
  const double period = *std::max_element(frame_period_s_.begin(), frame_period_s_.end());
  const double coasted = ToSeconds(t - *last_taken_t_);
  if (!(period > 0.0) || coasted <= 1.5 * period || coasted < options_.past_end_min_coast_s) {
    return false;
  }
  const auto velocity = tracker_.PredictVelocity(t);
  return velocity && std::abs(predicted->x()) > table::kHalfLength &&
         predicted->x() * velocity->x() > 0.0;
}

bool FrameSetTracker::SizeFits(double diameter_px, double expected_px) const {
  if (!(expected_px > 0.0)) return false;
  const double ratio = diameter_px / expected_px;
  return ratio <= options_.max_size_ratio && ratio >= options_.min_fragment_ratio;
}

bool FrameSetTracker::ViewSizeFits(double diameter_px, double expected_px) const {
  return SizeFits(diameter_px, expected_px) &&
         diameter_px <= options_.max_view_size_ratio * expected_px +
                            options_.view_size_margin_sigmas * options_.diameter_sigma;
}

bool FrameSetTracker::Fragment(double diameter_px, double expected_px) const {
  return diameter_px < options_.min_size_ratio * expected_px;
}

std::vector<FrameSetTracker::Hypothesis> FrameSetTracker::Hypotheses(
    const std::vector<std::vector<Detection>>& candidates) const {
  const int n = rig_.size();
  std::vector<Hypothesis> out;
  std::vector<Observation> observations;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int a = 0; a < static_cast<int>(candidates[i].size()); ++a) {
        for (int b = 0; b < static_cast<int>(candidates[j].size()); ++b) {
          const Detection& da = candidates[i][a];
          const Detection& db = candidates[j][b];
          if (EpipolarDistance(rig_.cameras[i], da.pixel, rig_.cameras[j], db.pixel) >
              options_.epipolar_px) {
            continue;
          }
          observations = {{i, da.pixel}, {j, db.pixel}};
          auto estimate = TriangulateObservations(rig_.cameras, observations, triangulation_);
          if (!estimate) continue;
          Hypothesis h;
          h.members = {{i, a}, {j, b}};
          // Other views: the candidate nearest to the point's projection, if near enough and
          // of a size the ball may have there (misfit_view_rejects_pair).
          bool misfit = false;
          // A third view smaller than a half-hidden ball there (a fragment: the core of a fast
          // ball's streak, the lit part of a shaded one) joins no whole pair: it would make the
          // point a fragment that starts no track, while the pair alone fixes it.
          const bool pair_whole =
              !Fragment(da.diameter_px, ExpectedDiameterPx(rig_.cameras[i], estimate->point)) &&
              !Fragment(db.diameter_px, ExpectedDiameterPx(rig_.cameras[j], estimate->point));
          for (int k = 0; k < n; ++k) {
            if (k == i || k == j) continue;
            const auto px = rig_.cameras[k].Project(estimate->point);
            if (!px) continue;
            int best_k = -1;
            double best_d = options_.reprojection_px;
            for (int m = 0; m < static_cast<int>(candidates[k].size()); ++m) {
              const double d = (candidates[k][m].pixel - *px).norm();
              if (d < best_d) best_d = d, best_k = m;
            }
            if (best_k < 0) continue;
            const double expected_k = ExpectedDiameterPx(rig_.cameras[k], estimate->point);
            if (!ViewSizeFits(candidates[k][best_k].diameter_px, expected_k)) {
              misfit = true;
              continue;
            }
            if (pair_whole && Fragment(candidates[k][best_k].diameter_px, expected_k)) continue;
            h.members.emplace_back(k, best_k);
            observations.push_back({k, candidates[k][best_k].pixel});
          }
          if (misfit && options_.misfit_view_rejects_pair) continue;
          if (h.members.size() > 2) {
            estimate = TriangulateObservations(rig_.cameras, observations, triangulation_);
            if (!estimate) continue;
          }
          if (estimate->mean_reprojection_px > options_.reprojection_px) continue;
          // In the hall, above its floor (the floor is 0.76 m below the table top).
          const Eigen::Vector3d& q = estimate->point;
          if (q.z() < table::kFloorZ - 0.02 || q.z() > options_.hall_half_size.z() ||
              std::abs(q.x()) > options_.hall_half_size.x() ||
              std::abs(q.y()) > options_.hall_half_size.y()) {
            continue;
          }
          h.estimate = *estimate;
          // The ball's known size (paper §3.2) at the point found: a head, a shirt or a speck of
          // noise that happens to meet an epipolar line is the wrong size in some view.
          bool sized = true;
          std::vector<Observation> shaded;  // the views' centres moved back from shade
          for (const auto& [c, m] : h.members) {
            const double expected = ExpectedDiameterPx(rig_.cameras[c], estimate->point);
            // A view short of the ball's size there has its centre known the less (a faint
            // streak's width is no measure of what is hidden).
            const Detection& view = candidates[c][m];
            const double short_px = view.streak ? 0.0 : std::max(0.0, expected - view.diameter_px);
            shaded.push_back(
                {c, ShadedCentre(view, expected), options_.misfit_sigma_share * short_px});
            if (!ViewSizeFits(view.diameter_px, expected)) {
              sized = false;
              break;
            }
            // Smaller than a half-hidden ball: the part of a shaded ball that the tables took.
            if (Fragment(view.diameter_px, expected)) h.fragment = true;
            h.size_misfit += std::abs(std::log(view.diameter_px / expected));
          }
          if (!sized) continue;
          if (options_.shade_correction) {
            if (auto e = TriangulateObservations(rig_.cameras, shaded, triangulation_))
              h.estimate = *e;
          }
          out.push_back(std::move(h));
        }
      }
    }
  }
  const auto score = [](const Hypothesis& h) {
    return h.size_misfit + 0.05 * h.estimate.mean_reprojection_px;
  };
  std::stable_sort(out.begin(), out.end(), [&](const Hypothesis& a, const Hypothesis& b) {
    if (a.members.size() != b.members.size()) return a.members.size() > b.members.size();
    if (a.fragment != b.fragment) return b.fragment;
    return score(a) < score(b);
  });
  return out;
}

bool FrameSetTracker::OutlineShortViews(const std::vector<Hypothesis>& hypotheses,
                                        const std::optional<Eigen::Vector3d>& predicted,
                                        std::span<const std::optional<ImageView>> images,
                                        std::vector<std::vector<Detection>>* candidates) const {
  std::vector<int> order(hypotheses.size());
  std::iota(order.begin(), order.end(), 0);
  if (predicted) {
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return (hypotheses[a].estimate.point - *predicted).squaredNorm() <
             (hypotheses[b].estimate.point - *predicted).squaredNorm();
    });
  }
  bool changed = false;
  std::vector<std::pair<int, int>> tried;
  for (int i : order) {
    const Hypothesis& h = hypotheses[i];
    for (const auto& [c, k] : h.members) {
      if (std::find(tried.begin(), tried.end(), std::make_pair(c, k)) != tried.end()) continue;
      tried.emplace_back(c, k);
      Detection& d = (*candidates)[c][k];
      if (c >= static_cast<int>(images.size()) || !images[c] || d.streak || d.by_coverage ||
          d.cut || d.in_merged || d.outlined) {
        continue;
      }
      const double expected = ExpectedDiameterPx(rig_.cameras[c], h.estimate.point);
      const double width = d.edge_width_px > 0.0 ? d.edge_width_px : d.diameter_px;
      if (!(expected >= options_.outline_min_diameter_px) ||
          width >= options_.outline_short_ratio * expected ||
          width < options_.outline_min_ratio * expected) {
        continue;
      }
      double colour[3];
      if (!segment::ColourAt(*images[c], d.observed.x(), d.observed.y(), colour)) continue;
      // The faint side, the view's own or its camera's: the cap lies away from it.
      const Eigen::Vector2d faint = FaintSide(d);
      const bool sided = !faint.isZero();
      const double max_shift =
          sided ? options_.outline_sided_shift_share * 0.5 * expected +
                      options_.outline_shift_margin_px
                : std::max(0.0, 0.5 * (expected - width)) + options_.outline_shift_margin_px;
      const auto fit = segment::FitOutline(*images[c], d.observed.x(), d.observed.y(),
                                           0.5 * expected, max_shift, colour, options_.outline);
      if (!fit) continue;
      // Toward the faint side only: a pull the other way is the lamp-lit surroundings (a
      // banner's lettering of the ball's colour above a yellow ball).
      if (sided && (Eigen::Vector2d(fit->cx, fit->cy) - d.observed).dot(faint.normalized()) <
                       -options_.outline_shift_margin_px) {
        continue;
      }
      // Its diameter measured: the hypothesis's size check holds it.
      Remeasure({fit->cx, fit->cy}, 2.0 * fit->radius, &d);
      d.outlined = true;
      changed = true;
    }
  }
  return changed;
}

bool FrameSetTracker::WholeFragments(const std::vector<Hypothesis>& hypotheses,
                                     std::span<const std::optional<ImageView>> images,
                                     std::vector<std::vector<Detection>>* candidates) const {
  bool changed = false;
  std::vector<std::pair<int, int>> tried;
  for (const Hypothesis& h : hypotheses) {
    if (!h.fragment) continue;
    for (const auto& [c, k] : h.members) {
      Detection& d = (*candidates)[c][k];
      const double expected = ExpectedDiameterPx(rig_.cameras[c], h.estimate.point);
      if (c >= static_cast<int>(images.size()) || !images[c] || d.streak || d.by_coverage ||
          d.cut || expected <= 0.0 || !Fragment(d.diameter_px, expected) ||
          std::find(tried.begin(), tried.end(), std::make_pair(c, k)) != tried.end()) {
        continue;
      }
      tried.emplace_back(c, k);
      const auto e = segment::MeasureEdgeCentre(*images[c], d.observed.x(), d.observed.y(),
                                                0.5 * expected, options_.edge);
      if (!e || !EdgeGivesDiameter(*e, options_.edge_diameter_max_elongation) ||
          std::hypot(e->cx - d.observed.x(), e->cy - d.observed.y()) > 0.5 * expected) {
        continue;
      }
      // The ball's own size, not another fragment (a half-hidden ball is no reason here).
      const double ratio = e->minor_diameter / expected;
      if (ratio < 1.0 / options_.max_size_ratio || ratio > options_.max_size_ratio) continue;
      Remeasure({e->cx, e->cy}, e->minor_diameter, &d);
      changed = true;
    }
  }
  return changed;
}

bool FrameSetTracker::SearchEpipolars(const std::vector<Hypothesis>& hypotheses,
                                      const std::optional<Eigen::Vector3d>& predicted,
                                      const Eigen::Matrix3d& predicted_covariance,
                                      std::span<const std::optional<ImageView>> images,
                                      const std::function<bool(int)>& in_step,
                                      std::vector<std::vector<Detection>>* candidates) const {
  const bool placed = std::any_of(hypotheses.begin(), hypotheses.end(), [&](const Hypothesis& h) {
    return !h.fragment && (!predicted || (h.estimate.point - *predicted).norm() <=
                                             options_.max_prediction_distance);
  });
  if (placed) return false;
  const EpipolarSearchOptions& search = options_.epipolar;
  const int n = rig_.size();
  const auto has_image = [&](int c) {
    return c < static_cast<int>(images.size()) && images[c] && in_step(c);
  };
  std::vector<std::vector<Detection>> found(n);
  for (int a = 0; a < n; ++a) {
    if (!has_image(a)) continue;
    const std::vector<Detection>& views = (*candidates)[a];
    std::vector<int> order;
    for (int k = 0; k < static_cast<int>(views.size()); ++k) {
      const Detection& d = views[k];
      if (!d.streak && !d.still && !d.cut && d.diameter_px >= 2.0) order.push_back(k);
    }
    if (predicted) {
      if (const auto px = rig_.cameras[a].Project(*predicted)) {
        std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
          return (views[i].pixel - *px).squaredNorm() < (views[j].pixel - *px).squaredNorm();
        });
      }
    }
    if (static_cast<int>(order.size()) > options_.search_views_per_camera) {
      order.resize(options_.search_views_per_camera);
    }
    for (int k : order) {
      const Detection& d = views[k];
      // The view's own colour, and whether it is round at all.
      const auto own = segment::MeasureEdgeCentre(*images[a], d.observed.x(), d.observed.y(),
                                                  0.5 * d.diameter_px, options_.edge);
      if (!own || !EdgeGivesDiameter(*own, search.max_elongation)) continue;
      for (int b = 0; b < n; ++b) {
        if (b == a || !has_image(b)) continue;
        const auto hit = SearchAlongEpipolar(rig_.cameras[a], d.pixel, d.diameter_px, own->colour,
                                             rig_.cameras[b], *images[b], search);
        if (!hit) continue;
        const auto near = [&](const Detection& e) {
          return (e.pixel - hit->pixel).norm() < 0.5 * hit->diameter_px;
        };
        if (std::any_of((*candidates)[b].begin(), (*candidates)[b].end(), near) ||
            std::any_of(found[b].begin(), found[b].end(), near)) {
          continue;
        }
        Detection view = DiscView(b, hit->pixel, hit->diameter_px);
        // Far from the track's prediction (beyond 99 % of its covariance and a centimetre): a
        // view for a new track only (Detection::outside), never a measurement of this one.
        view.outside = d.outside;
        if (predicted) {
          const Eigen::Vector3d off = hit->point - *predicted;
          const Eigen::Matrix3d spread = predicted_covariance + 1e-4 * Eigen::Matrix3d::Identity();
          view.outside = view.outside ||
                         off.dot(spread.ldlt().solve(off)) > options_.lone_view_consistency_chi2;
        }
        found[b].push_back(view);
      }
    }
  }
  bool any = false;
  for (int b = 0; b < n; ++b) {
    for (Detection& view : found[b]) (*candidates)[b].push_back(view);
    any = any || !found[b].empty();
  }
  return any;
}

const FrameSetTracker::Hypothesis* FrameSetTracker::Pick(
    const std::vector<Hypothesis>& hypotheses,
    const std::optional<Eigen::Vector3d>& predicted) const {
  // A fragment is the ball only where the track expects it.
  const auto usable = [&](const Hypothesis& h) {
    return !h.fragment ||
           (predicted && (h.estimate.point - *predicted).norm() <= options_.fragment_max_distance);
  };
  const Hypothesis* best = nullptr;
  for (const Hypothesis& h : hypotheses) {
    if (!usable(h)) continue;
    if (!best) {
      best = &h;
      if (!predicted) break;
      continue;
    }
    // Distance to the prediction ranks hypotheses of as many views; it never rejects one (a
    // wrong track must not hide the ball: the filter's gate and the initiator judge).
    if (h.members.size() < best->members.size()) break;
    if ((h.estimate.point - *predicted).norm() < (best->estimate.point - *predicted).norm()) {
      best = &h;
    }
  }
  return best;
}

Measurement FrameSetTracker::ToMeasurement(const Hypothesis& h) const {
  Measurement m;
  m.position = h.estimate.point;
  m.cameras = static_cast<int>(h.members.size());
  m.residual_px = h.estimate.mean_reprojection_px;
  // Isotropic covariance from the centroid noise at the views' mean depth (a fair bound for
  // cameras that see the ball from well-separated directions).
  double depth = 0.0, focal = 0.0;
  for (const auto& [c, k] : h.members) {
    depth += (rig_.cameras[c].cam_from_world * m.position).z();
    focal += rig_.cameras[c].fx;
  }
  const double sigma = std::max(0.001, 1.5 * options_.pixel_sigma * depth / focal /
                                           std::sqrt(static_cast<double>(m.cameras) - 1.0));
  m.covariance = sigma * sigma * Eigen::Matrix3d::Identity();
  return m;
}

std::optional<Measurement> FrameSetTracker::SingleView(
    const std::vector<Detection>& views, const std::vector<std::optional<Measurement>>& placed,
    const std::optional<Eigen::Vector3d>& predicted, const Eigen::Matrix3d& predicted_covariance,
    std::span<const double> motion_px, std::vector<std::pair<int, int>>* used) const {
  std::optional<Measurement> best;
  double best_score = 0.0;
  int best_k = 0;
  const double expected = predicted ? ExpectedDiameterPx(rig_.cameras[0], *predicted) : 0.0;
  for (int k = 0; k < static_cast<int>(views.size()); ++k) {
    const std::optional<Measurement>& m = placed[k];
    if (!m || NotPredictedBall(views[k], expected, motion_px[0])) continue;
    // Without a prediction the largest region is the ball (paper §3.1); with one, the closest.
    double score = -static_cast<double>(views[k].area_px);
    if (predicted) {
      const Eigen::Vector3d r = m->position - *predicted;
      if (r.norm() > options_.max_prediction_distance) continue;
      // Mahalanobis: the view's depth by its diameter is known to a few per cent of the
      // distance, its direction to a pixel; the nearest in metres would be the one whose
      // diameter happens to err towards the prediction.
      score = r.dot((m->covariance + predicted_covariance).ldlt().solve(r));
    }
    if (best && score >= best_score) continue;
    best = m;
    best_score = score;
    best_k = k;
  }
  if (best) *used = {{0, best_k}};
  return best;
}

std::vector<double> FrameSetTracker::PredictedMotion(const Eigen::Vector3d& predicted,
                                                     const Eigen::Vector3d& velocity) const {
  std::vector<double> motion(rig_.size(), std::numeric_limits<double>::quiet_NaN());
  for (int c = 0; c < rig_.size(); ++c) {
    const double period = frame_period_s_[c];
    if (!(period > 0.0)) continue;
    const Camera& camera = rig_.cameras[c];
    const auto a = camera.Project(predicted - 0.5 * period * velocity);
    const auto b = camera.Project(predicted + 0.5 * period * velocity);
    if (a && b) motion[c] = (*b - *a).norm();
  }
  return motion;
}

bool FrameSetTracker::NotPredictedBall(const Detection& d, double expected_px,
                                       double motion_px) const {
  if (std::isnan(motion_px)) return false;  // nothing known of its travel
  if (d.still && motion_px > options_.still_max_motion_px) return true;
  if (!(d.length_px > 0.0)) return false;
  const double longest = options_.blur_size_share * std::max(d.diameter_px, expected_px) +
                         options_.blur_motion_share * motion_px + options_.blur_margin_px;
  return d.length_px > longest;
}

std::optional<Measurement> FrameSetTracker::SphereMeasurement(const Camera& camera,
                                                              const Detection& d) const {
  if (d.cut) return std::nullopt;
  // The detection's diameter is the blur-proof minor axis, across the image radius.
  const auto sphere = PointFromSphereImage(camera, d.pixel, d.diameter_px,
                                           EllipseAxis::kAcrossRadius, table::kBallRadius);
  if (!sphere) return std::nullopt;
  const Eigen::Vector3d& q = sphere->point;  // in the hall, above the floor
  if (std::abs(q.x()) > options_.hall_half_length || std::abs(q.y()) > options_.hall_half_width ||
      q.z() < table::kFloorZ || q.z() > options_.hall_max_z) {
    return std::nullopt;
  }
  Measurement m;
  m.cameras = 1;
  const Eigen::Vector3d ray = (sphere->point - camera.Center()).normalized();
  const Eigen::Matrix3d across_ray = Eigen::Matrix3d::Identity() - ray * ray.transpose();
  const double across = sphere->distance * options_.pixel_sigma / camera.fx;
  m.position = sphere->point;
  const double along = sphere->distance * options_.diameter_sigma / std::max(1.0, d.diameter_px);
  m.covariance = along * along * ray * ray.transpose() + across * across * across_ray;
  return m;
}

std::optional<FrameSetTracker::LoneView> FrameSetTracker::NearestLoneView(
    const std::vector<std::vector<Detection>>& candidates, const Eigen::Vector3d& predicted,
    const Eigen::Matrix3d& predicted_covariance, std::span<const double> motion_px) const {
  std::optional<LoneView> best;
  double best_d2 = 0.0;
  for (int c = 0; c < rig_.size(); ++c) {
    if (candidates[c].empty()) continue;
    const Camera& camera = rig_.cameras[c];
    const auto centre = camera.Project(predicted);
    if (!centre) continue;
    // The prediction's covariance in the image: J P J^T (J by differences of 1 mm) plus the
    // view's own noise.
    Eigen::Matrix<double, 2, 3> jacobian;
    bool projects = true;
    for (int i = 0; i < 3 && projects; ++i) {
      const auto moved = camera.Project(predicted + 1e-3 * Eigen::Vector3d::Unit(i));
      projects = moved.has_value();
      if (projects) jacobian.col(i) = (*moved - *centre) / 1e-3;
    }
    if (!projects) continue;
    const Eigen::Matrix2d image_covariance =
        jacobian * predicted_covariance * jacobian.transpose() +
        options_.pixel_sigma * options_.pixel_sigma * Eigen::Matrix2d::Identity();
    // A prediction that cannot tell the ball from what lies a diameter beside it (a track that
    // coasted) is not continued by one view.
    const double expected = ExpectedDiameterPx(camera, predicted);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(image_covariance);
    if (std::sqrt(std::max(0.0, spread.eigenvalues().maxCoeff())) >
        options_.lone_view_image_sigma * expected) {
      continue;
    }
    const Eigen::Matrix2d information = image_covariance.inverse();
    for (int k = 0; k < static_cast<int>(candidates[c].size()); ++k) {
      const Detection& d = candidates[c][k];
      // A disc found inside a larger region where the track predicted it says nothing by itself
      // that the prediction did not (its place was searched there, its size is the expected one).
      if (d.in_merged || NotPredictedBall(d, expected, motion_px[c])) continue;
      const Eigen::Vector2d r = d.pixel - *centre;
      const double d2 = r.dot(information * r);
      if (d2 > options_.lone_view_gate_chi2 || (best && d2 >= best_d2)) continue;
      LoneView lone;
      lone.id = {c, k};
      // (The view's centre moved back from its faint side by the width it lost against the
      // ball's at the predicted point.)
      lone.ray = camera.RayDirection(ShadedCentre(d, expected));
      lone.depth_sigma = std::sqrt(lone.ray.dot(predicted_covariance * lone.ray));
      // The view fixes the ball's direction; its depth along the ray comes from the filter's
      // prediction, which beats the diameter's (paper §3.2: "error-prone")...
      const double depth = std::max(0.1, (predicted - camera.Center()).dot(lone.ray));
      // ...but the diameter must agree with it (3 sigmas of both); a streak's diameter is the
      // expected one or a guess from its share: no evidence.
      if (!d.streak) {
        const auto sphere = PointFromSphereImage(camera, d.pixel, d.diameter_px,
                                                 EllipseAxis::kAcrossRadius, table::kBallRadius);
        if (!sphere) continue;
        const double sigma =
            sphere->distance * options_.diameter_sigma / std::max(1.0, d.diameter_px);
        if (std::abs(sphere->distance - depth) > 3.0 * std::hypot(sigma, lone.depth_sigma)) {
          continue;
        }
      }
      const double across = depth * options_.pixel_sigma / camera.fx;
      const double along = options_.single_view_depth_sigma;
      Measurement& m = lone.measurement;
      m.cameras = 1;
      m.position = camera.Center() + depth * lone.ray;
      m.covariance =
          along * along * lone.ray * lone.ray.transpose() +
          across * across * (Eigen::Matrix3d::Identity() - lone.ray * lone.ray.transpose());
      best = lone;
      best_d2 = d2;
    }
  }
  return best;
}

void FrameSetTracker::PlaceLoneViews(FrameSetResult* result) {
  const TimeNs hold = FromSeconds(options_.initiator.max_span_s);
  std::erase_if(waiting_, [&](const WaitingView& w) { return result->t - w.t > hold; });
  while (!fixes_.empty() && result->t - fixes_.front() > hold) fixes_.pop_front();
  // A step that took no measurement changes no smoothed state before it, nor the fixes: the
  // waiting views' verdicts stay as they were.
  if (waiting_.empty() || !result->state || !result->state->measured) return;
  const std::vector<FilterStep>& steps = tracker_.history();
  const std::vector<SmoothedState> smoothed = SmoothSteps(steps);
  std::erase_if(waiting_, [&](const WaitingView& w) {
    const auto it = std::find_if(smoothed.begin(), smoothed.end(),
                                 [&](const SmoothedState& s) { return s.t == w.t; });
    if (it == smoothed.end()) return true;  // no longer in the track's history
    // Its track must follow the model everywhere (no measurement beyond 99 % of its prior): a
    // hit the filter went through bends the smoothed path on both sides of it.
    const auto i = it - smoothed.begin();
    auto first = i, last = i;
    while (first > 0 && !steps[first].start) --first;
    while (last + 1 < static_cast<long>(steps.size()) && !steps[last + 1].start) ++last;
    for (auto k = first; k <= last; ++k) {
      if (steps[k].innovation_chi2 > options_.lone_view_consistency_chi2) return false;
    }
    // Between fixes, not after the last: two views of the ball after it in the same track.
    if (std::none_of(fixes_.begin(), fixes_.end(),
                     [&](TimeNs f) { return f > w.t && f <= steps[last].t; })) {
      return false;
    }
    const Eigen::Matrix3d covariance = it->covariance.topLeftCorner<3, 3>();
    if (std::sqrt(w.ray.dot(covariance * w.ray)) > options_.single_view_max_depth_sigma) {
      return false;
    }
    // The smoothed track must pass through the view (3 pixel sigmas): one that misses it was
    // pulled by a measurement after a hit or of something else.
    const auto seen = rig_.cameras[w.camera].Project(it->state.head<3>());
    if (!seen || (*seen - w.pixel).norm() > 3.0 * options_.pixel_sigma) return true;
    Revision r;
    r.t = w.t;
    r.measurement.position = it->state.head<3>();
    r.measurement.covariance = covariance;
    r.measurement.cameras = 1;
    r.state.t = w.t;
    r.state.position = it->state.head<3>();
    r.state.velocity = it->state.tail<3>();
    r.state.measured = true;
    r.state.cameras = 1;
    r.accepted = {w.detection};
    result->revisions.push_back(std::move(r));
    return true;
  });
  std::stable_sort(result->revisions.begin(), result->revisions.end(),
                   [](const Revision& a, const Revision& b) { return a.t < b.t; });
}

double RowHoldSeconds(const FrameSetOptions& options) {
  return options.initiator.max_span_s + options.tracker.fall.window_s;
}

void ClearMeasurement(FrameSetResult* result) {
  result->measurement.reset();
  for (Detection& d : result->detections) d.accepted = false;
  if (result->state) {
    result->state->measured = false;
    result->state->cameras = 0;
  }
}

}  // namespace p4::track
