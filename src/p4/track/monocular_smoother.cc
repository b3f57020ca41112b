#include "p4/track/monocular_smoother.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "p4/core/table.h"
#include "p4/geometry/sphere_depth.h"

namespace p4::track {
namespace {

// Least-squares polynomial of `degree` in (t - t_ref) through the views' ideal pixels,
// evaluated at t_ref.
template <typename Views>
Eigen::Vector2d PolynomialAt(const Views& views, double t_ref, int degree) {
  const int n = static_cast<int>(views.size());
  Eigen::MatrixXd a(n, degree + 1);
  Eigen::MatrixXd b(n, 2);
  for (int i = 0; i < n; ++i) {
    const double dt = views[i].t - t_ref;
    double power = 1.0;
    for (int k = 0; k <= degree; ++k, power *= dt) a(i, k) = power;
    b.row(i) = views[i].ideal_px.transpose();
  }
  const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(b);
  return x.row(0).transpose();
}
template <typename Views>
Eigen::Vector2d QuadraticAt(const Views& views, double t_ref) {
  return PolynomialAt(views, t_ref, 2);
}

}  // namespace

bool MonocularSmootherOptions::IsValid(std::string* error) const {
  if (!fit.IsValid(error)) return false;
  if (!(pixel_sigma > 0.0 && diameter_sigma > 0.0 && kink_px > 0.0 && bend_px >= kink_px &&
        adopt_px >= 0.0 && max_gap_s > 0.0 && lead_max_gap_frames > 0.0 && max_window_s > 0.0 &&
        contact_margin >= 0.0 && start_contact_height >= 0.0 && contact_depth_agree > 0.0 &&
        contact_depth_agree_share >= 0.0 && bounce_speed_slack >= 0.0 &&
        bounce_min_up_across >= 0.0 && max_fit_rms > 0.0 && max_fit_rms_short > 0.0 &&
        merge_rms > 0.0 && max_distance_error > 0.0)) {
    *error = "monocular smoother: sigmas, thresholds and times must be positive";
    return false;
  }
  if (window < 4 || kink_views < 1 || min_piece_views < 4) {
    *error = "monocular smoother: window and min_piece_views must be >= 4, kink_views >= 1";
    return false;
  }
  return true;
}

MonocularSmoother::MonocularSmoother(const Camera& camera, const MonocularSmootherOptions& options)
    : camera_(camera), options_(options) {}

std::optional<Eigen::Vector2d> MonocularSmoother::PathAt(const Piece& piece, double t) const {
  if (piece.size() < 4) return std::nullopt;
  const size_t n = std::min<size_t>(piece.size(), options_.window);
  return QuadraticAt(std::span(piece.end() - n, piece.end()), t);
}

Eigen::Vector2d MonocularSmoother::IdealPixel(const Eigen::Vector2d& pixel) const {
  return camera_.fx * camera_.NormalizedFromPixel(pixel);
}

std::optional<MonocularSmoother::View> MonocularSmoother::ViewFrom(const FrameSetResult& result,
                                                                   const Detection& d) const {
  // A region at the image's edge is a ball cut by it: neither its centre nor its size is the
  // ball's.
  if (d.cut) return std::nullopt;
  const auto sphere = PointFromSphereImage(
      camera_, d.pixel, d.diameter_px, EllipseAxis::kAcrossRadius, options_.fit.model.ball_radius);
  if (!sphere) return std::nullopt;
  View v;
  v.t = ToSeconds(result.t);
  v.ideal_px = IdealPixel(d.pixel);
  BearingObservation& o = v.bearing;
  o.t = v.t;
  o.origin = camera_.Center();
  o.direction = camera_.RayDirection(d.pixel);
  o.angle_sigma = options_.pixel_sigma / camera_.fx;
  o.distance = sphere->distance;
  o.distance_sigma = sphere->distance * options_.diameter_sigma / std::max(1.0, d.diameter_px);
  return v;
}

std::optional<MonocularSmoother::View> MonocularSmoother::ViewOf(
    const FrameSetResult& result) const {
  if (!result.measurement || result.measurement->cameras != 1) return std::nullopt;
  for (const Detection& d : result.detections) {
    if (d.accepted) return ViewFrom(result, d);
  }
  return std::nullopt;
}

std::optional<MonocularSmoother::View> MonocularSmoother::Adopt(
    FrameSetResult* result, const std::optional<Eigen::Vector2d>& path) const {
  std::optional<View> view = ViewOf(*result);
  if (!path || !off_.empty()) return view;
  // A candidate on the open piece's path is the ball, whether the filter took it or not (from
  // one camera a filter that went astray in depth gates the ball out, while its image path goes
  // on plainly).
  const Eigen::Vector2d& expected = *path;
  if (view && (view->ideal_px - expected).norm() <= options_.kink_px) return view;
  int best = -1;
  double best_d = options_.adopt_px;
  for (int k = 0; k < static_cast<int>(result->detections.size()); ++k) {
    const double d = (IdealPixel(result->detections[k].pixel) - expected).norm();
    if (d <= best_d) best_d = d, best = k;
  }
  if (best < 0) return view;
  std::optional<View> adopted = ViewFrom(*result, result->detections[best]);
  if (!adopted) return view;
  for (int k = 0; k < static_cast<int>(result->detections.size()); ++k) {
    result->detections[k].accepted = k == best;
  }
  const BearingObservation& o = adopted->bearing;
  const Eigen::Vector3d p = o.origin + o.distance * o.direction;  // until a fit places it
  if (!result->measurement) result->measurement = Measurement{};
  result->measurement->position = p;
  result->measurement->cameras = 1;
  result->measurement->residual_px = 0.0;
  if (!result->state) {
    result->state = TrackedState{};
    result->state->t = result->t;
    result->state->position = p;
  }
  result->state->measured = true;
  result->state->cameras = 1;
  return adopted;
}

std::vector<FrameSetResult> MonocularSmoother::Push(FrameSetResult result) {
  held_.push_back(std::move(result));
  placed_.push_back(0);
  // Where the open piece's path is at this time (with 4 views or more).
  const std::optional<Eigen::Vector2d> path = PathAt(piece_, ToSeconds(held_.back().t));
  const std::optional<View> view = Adopt(&held_.back(), path);
  if (view) {
    const View* last = !off_.empty() ? &off_.back() : !piece_.empty() ? &piece_.back() : nullptr;
    const double window_start = lead_in_           ? lead_in_->after_t
                                : !window_.empty() ? window_.front().front().t
                                : !piece_.empty()  ? piece_.front().t
                                                   : view->t;
    if (last && view->t - last->t > options_.max_gap_s) {
      EndPiece({});  // the ball was out of sight: the chain breaks
    } else if (view->t - window_start > options_.max_window_s && !window_.empty() &&
               !pending_bend_) {
      FitWindow(false);  // no bounce for long: hand the window on, the chain goes on
    }
    // (A gap just ended the piece the path was of: a new one starts with this view.)
    const double off_by = path && !piece_.empty() ? (*path - view->ideal_px).norm() : 0.0;
    if (off_by > options_.kink_px) {
      off_.push_back(*view);
      // A bend leaves the path ever farther; a view pulled aside by something next to the ball
      // (an arm, the net's edge) does not.
      const int n = static_cast<int>(off_.size());
      if ((n >= options_.kink_views && off_by >= options_.bend_px) ||
          n >= 2 * options_.kink_views) {
        const Piece next = off_;
        off_.clear();
        EndPiece(next);
      }
    } else {
      off_.clear();  // strays between views that fit
      piece_.push_back(*view);
      // A piece's first view may be the bend's own moment (the racket's contact, then frames
      // the detector missed while the ball was fast): the line of the three views after it,
      // taken back to it, tells (before the piece's path, which it would bend, is used); off by
      // a bend, it belongs to neither piece.
      if (piece_.size() == 4 &&
          (PolynomialAt(std::span(piece_.begin() + 1, piece_.end()), piece_.front().t, 1) -
           piece_.front().ideal_px)
                  .norm() > options_.bend_px) {
        Unmeasure(piece_.front().t);
        piece_.erase(piece_.begin());
        // Without it the views on either side of the bend may lie too far apart to be joined
        // (another bend may hide between them: a return stopped by the net): the chain breaks.
        if (pending_bend_ && !window_.empty() &&
            piece_.front().t - window_.back().back().t > options_.max_gap_s) {
          BreakChain({});
        }
      }
    }
    if (pending_bend_ && static_cast<int>(piece_.size()) >= options_.min_piece_views) {
      DecideBend();
    }
  }
  // Held: the views still open, orphans a window may yet reach, and the rows after the lead-in
  // while a window may still start from it (not through the pause between points).
  const double now = ToSeconds(held_.back().t);
  std::erase_if(orphans_, [&](const Piece& p) { return now - p.back().t > options_.max_gap_s; });
  double open_from = std::numeric_limits<double>::infinity();
  if (!window_.empty()) open_from = window_.front().front().t;
  if (!piece_.empty()) open_from = std::min(open_from, piece_.front().t);
  if (!off_.empty()) open_from = std::min(open_from, off_.front().t);
  if (lead_in_ && std::min(now, open_from) - lead_in_->after_t <= options_.max_gap_s) {
    open_from = std::min(open_from, lead_in_->after_t + 1e-6);
  }
  if (!orphans_.empty()) open_from = std::min(open_from, orphans_.front().front().t);
  return Release(open_from);
}

std::vector<FrameSetResult> MonocularSmoother::Flush() {
  EndPiece({});
  return Release(std::numeric_limits<double>::infinity());
}

void MonocularSmoother::EndPiece(const Piece& next) {
  if (static_cast<int>(piece_.size()) < options_.min_fit_views) {
    BreakChain(piece_);
  } else {
    if (pending_bend_) DecideBend();
    window_.push_back(piece_);
    pending_bend_ = true;
  }
  piece_ = next;
  off_.clear();
  if (next.empty()) BreakChain({});
}

bool MonocularSmoother::Holds(const std::optional<Stroke>& fit, double max_rms) const {
  return fit && fit->rms_bearing <= max_rms &&
         fit->median_distance_error <= options_.max_distance_error && !fit->scale_at_bound;
}

void MonocularSmoother::DecideBend() {
  pending_bend_ = false;
  // A bend that one flight explains was none (the ball passing the net's edge, an arm beside it
  // pulling a view or two aside): the two pieces are one.
  Piece merged = window_.back();
  merged.insert(merged.end(), piece_.begin(), piece_.end());
  std::vector<BearingObservation> obs;
  for (const View& v : merged) obs.push_back(v.bearing);
  Stroke one;
  one.pieces = {QuadraticPiece(obs)};
  const auto fit = FitStroke(std::span(&obs, 1), one, options_.fit);
  if (fit && fit->rms_bearing <= options_.merge_rms) {
    window_.pop_back();
    piece_ = std::move(merged);
    return;
  }
  const Junction j = JunctionBetween(window_.back(), piece_);
  junctions_.push_back(j);
  if (j.on_plane) {
    ++bounces_found_;
    FitWindow(true);
  }
}

Junction MonocularSmoother::JunctionBetween(const Piece& before, const Piece& after) const {
  Junction j;
  j.t = 0.5 * (before.back().t + after.front().t);
  // The two sides' own account (their diameters, a free acceleration), at the bend.
  std::vector<BearingObservation> obs_before, obs_after;
  const size_t span = 24;
  for (size_t i = before.size() - std::min(before.size(), span); i < before.size(); ++i) {
    obs_before.push_back(before[i].bearing);
  }
  for (size_t i = 0; i < std::min(after.size(), span); ++i) obs_after.push_back(after[i].bearing);
  const Vector6d xb = PieceStateAt(QuadraticPiece(obs_before), j.t, options_.fit.model);
  const Vector6d xa = PieceStateAt(QuadraticPiece(obs_after), j.t, options_.fit.model);
  j.point = 0.5 * (xb.head<3>() + xa.head<3>());
  // A bounce: down, then up, the horizontal velocity kept in direction and mostly in size (a
  // hit turns it back, the net takes it). Judged on the parts across the ray, which the bearings
  // measure well (along it, a short piece's velocity is the diameters' noise): "up" is the
  // vertical less its part along the ray; a ball flying along the ray cannot be judged so and
  // passes, and so does the fall of a camera looking straight down.
  const Eigen::Vector3d c = camera_.Center();
  const Eigen::Vector3d ray = (j.point - c).normalized();
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(ray).normalized();
  const Eigen::Vector3d up_across = Eigen::Vector3d::UnitZ() - ray.z() * ray;
  const bool up_seen = up_across.norm() >= options_.bounce_min_up_across;
  const double vzb = up_seen ? up_across.normalized().dot(xb.tail<3>()) : xb(5);
  const double vza = up_seen ? up_across.normalized().dot(xa.tail<3>()) : xa(5);
  const double hb = across.dot(xb.tail<3>()), ha = across.dot(xa.tail<3>());
  const double ratio = ha / (std::abs(hb) > 1e-6 ? hb : 1e-6);
  const bool judged = std::max(std::abs(hb), std::abs(ha)) > options_.bounce_min_speed;
  // The table's friction changes the horizontal velocity by mu (1 + e) |vz| at most (sliding
  // through the contact): topspin may speed a slow ball up by more than the ratio allows.
  const FlightModel& model = options_.fit.model;
  const bool within_friction =
      std::abs(ha - hb) <=
      model.friction * (1.0 + model.restitution) * std::abs(vzb) + options_.bounce_speed_slack;
  if (!(vzb < 0.0 && vza > 0.0) ||
      (judged && !within_friction &&
       (ratio < options_.bounce_min_speed_ratio || ratio > options_.bounce_max_speed_ratio))) {
    return j;
  }
  // Where the ball was at the bend, in the image (both sides' quadratics), meets the plane.
  const size_t nb = std::min<size_t>(before.size(), options_.window);
  const size_t na = std::min<size_t>(after.size(), options_.window);
  const Eigen::Vector2d px = 0.5 * (QuadraticAt(std::span(before.end() - nb, before.end()), j.t) +
                                    QuadraticAt(std::span(after.begin(), after.begin() + na), j.t));
  const Eigen::Vector3d d = (camera_.cam_from_world.rotation.transpose() *
                             Eigen::Vector3d(px.x() / camera_.fx, px.y() / camera_.fx, 1.0))
                                .normalized();
  if (d.z() >= -1e-3) return j;  // the ray does not go down
  const double r = options_.fit.model.ball_radius;
  const double m = options_.contact_margin;
  for (const double plane_z : {r, table::kFloorZ + r}) {
    const double s = (plane_z - c.z()) / d.z();
    if (s <= 0.0) continue;
    const Eigen::Vector3d p = c + s * d;
    const bool on_table = table::OnSurface(p.x(), p.y(), m);
    if (on_table != (plane_z == r)) continue;  // the table top only on the table, the floor off it
    // The diameters of a ball blurred in a long exposure read short (its streak's sides are
    // covered for less of it): their distance may be long by a share of the contact's.
    const double agree =
        std::max(options_.contact_depth_agree, options_.contact_depth_agree_share * s);
    if (std::abs((xb.head<3>() - c).norm() - s) > agree ||
        std::abs((xa.head<3>() - c).norm() - s) > agree) {
      continue;
    }
    j.point = p;
    j.on_plane = true;
    return j;
  }
  return j;
}

void MonocularSmoother::FitWindow(bool with_open) {
  if (window_.empty()) return;
  // A short last piece after a free junction (a hit just before the ball was lost) would only
  // be held by its few diameters: it takes the distance where the flight before it ends. (Before
  // a bounce, the bounce holds it.)
  size_t closed = window_.size();
  while (!with_open && closed > 1 &&
         static_cast<int>(window_[closed - 1].size()) < options_.min_piece_views &&
         !junctions_[closed - 2].on_plane) {
    --closed;
  }
  std::vector<const Piece*> pieces;
  for (size_t i = 0; i < closed; ++i) pieces.push_back(&window_[i]);
  if (with_open && closed == window_.size() &&
      static_cast<int>(piece_.size()) >= options_.min_fit_views && junctions_.size() >= closed) {
    pieces.push_back(&piece_);
  }
  std::vector<std::vector<BearingObservation>> observations;
  Stroke guess;
  for (const Piece* piece : pieces) {
    std::vector<BearingObservation> obs;
    for (const View& v : *piece) obs.push_back(v.bearing);
    guess.pieces.push_back(QuadraticPiece(obs));
    observations.push_back(std::move(obs));
  }
  guess.junctions.assign(junctions_.begin(), junctions_.begin() + (pieces.size() - 1));
  const double t_first = window_.front().front().t, t_to = window_[closed - 1].back().t;
  const bool lead = lead_in_ && t_first - lead_in_->after_t <= options_.max_gap_s;
  // A window with a piece too short to judge its bends must fit well to be believed.
  const bool has_short = std::any_of(pieces.begin(), pieces.end(), [&](const Piece* p) {
    return static_cast<int>(p->size()) < options_.min_piece_views;
  });
  const double max_rms = has_short ? options_.max_fit_rms_short : options_.max_fit_rms;
  // A chain that starts as the ball leaves the table; else its first piece, slow and rising, is
  // the service toss (laws 2.6.2).
  std::optional<Stroke> fit, alone;
  if (!lead) {
    alone = FitStroke(observations, guess, options_.fit);  // no contact, no toss
    if (alone) fit = FitFromTable(observations, guess, *alone, max_rms);
  }
  if (!fit) {
    FlightPiece& first = guess.pieces.front();
    first.toss = !lead && first.state.tail<3>().norm() < options_.toss_max_speed &&
                 PieceStateAt(first, t_first, options_.fit.model)(5) > 0.0;
    if (lead) guess.start = lead_in_junction_;
    // A chain's first piece that is no toss was fitted alone already.
    fit = !lead && !first.toss
              ? alone
              : FitStroke(observations, guess, options_.fit, lead ? &*lead_in_ : nullptr);
  }
  const double t_from = lead ? lead_in_->after_t : t_first;
  std::optional<LeadIn> next;
  Junction next_junction;
  // Nothing but its diameters holds a lone window: it needs many of them.
  const int views = std::accumulate(pieces.begin(), pieces.end(), 0, [](int n, const Piece* p) {
    return n + static_cast<int>(p->size());
  });
  const bool held = lead || pieces.size() > 1 || views >= options_.min_lone_views;
  if (held && Holds(fit, max_rms)) {
    Apply(*fit, lead ? &lead_in_->piece : nullptr, t_from, t_to);
    ++windows_fitted_;
    next = LeadIn{fit->pieces[closed - 1], t_to};
    for (const Piece& orphan : orphans_) {
      if (t_first - orphan.back().t <= options_.max_gap_s && !lead) {
        Continue(fit->pieces.front(), orphan.front().t, orphan.back().t);
      }
    }
    if (closed < fit->pieces.size()) {
      next_junction = fit->junctions[closed - 1];
    } else if (junctions_.size() >= closed) {
      next_junction = junctions_[closed - 1];
    }
  } else {
    // The chain did not hold as a whole (a bend misjudged, a stretch of stray views): it is cut
    // into the longest runs of pieces that hold, first to last, each led in by the run before
    // (the ball leaves a hit where it arrived) where the views are close enough. A piece that no
    // run holds keeps the distance where the flight before it ended.
    std::optional<LeadIn> prev;
    std::optional<Junction> prev_junction;
    if (lead) prev = lead_in_, prev_junction = lead_in_junction_;
    size_t i = 0;
    while (i < closed) {
      const bool near = prev && observations[i].front().t - prev->after_t <= options_.max_gap_s;
      // Frames missed between them may hide another bend (a fast return stopped by the net): a
      // run is led in only across a gap of a few of its own frame periods.
      const double period = observations[i][1].t - observations[i][0].t;
      const bool leads = near && observations[i].front().t - prev->after_t <=
                                     options_.lead_max_gap_frames * period;
      std::optional<Stroke> run;
      size_t end = i;
      bool led = false;
      // Led in first; a run the lead-in does not fit (a bounce misjudged as free between them)
      // may stand alone. The longest run that holds wins.
      for (const bool with_lead : {true, false}) {
        if (with_lead && !leads) continue;
        for (size_t j = closed; j > i && !run; --j) {
          run = FitRun(observations, guess, i, j, with_lead ? &*prev : nullptr, prev_junction);
          end = j, led = with_lead;
        }
        if (run) break;
      }
      if (run) {
        const double from = led ? prev->after_t : observations[i].front().t;
        Apply(*run, led ? &prev->piece : nullptr, from, observations[end - 1].back().t);
        prev = LeadIn{run->pieces.back(), observations[end - 1].back().t};
        i = end;
      } else {
        if (near) {
          Continue(prev->piece, observations[i].front().t, observations[i].back().t);
          prev->after_t = observations[i].back().t;
        } else {
          prev.reset();
        }
        ++i;
      }
      // The junction where the next run starts: the bend judged after the last piece taken.
      if (i > 0 && i - 1 < junctions_.size()) prev_junction = junctions_[i - 1];
    }
    next = prev;
    if (junctions_.size() >= closed) next_junction = junctions_[closed - 1];
  }
  orphans_.clear();
  lead_in_ = next;
  lead_in_junction_ = next_junction;
  const size_t all = window_.size();
  for (size_t i = closed; i < window_.size() && lead_in_; ++i) {
    Continue(lead_in_->piece, window_[i].front().t, window_[i].back().t);
    lead_in_->after_t = window_[i].back().t;
  }
  window_.clear();
  junctions_.erase(junctions_.begin(), junctions_.begin() + std::min(junctions_.size(), all));
}

std::optional<Stroke> MonocularSmoother::FitFromTable(
    std::span<const std::vector<BearingObservation>> observations, Stroke guess,
    const Stroke& alone, double max_rms) const {
  const std::vector<BearingObservation>& first = observations.front();
  const double t_first = first.front().t;
  // Where the flight alone (no contact, no toss) has the ball at its first view.
  const Vector6d x = PieceStateAt(alone.pieces.front(), t_first, options_.fit.model);
  const double r = options_.fit.model.ball_radius;
  if (!(x(5) > 0.0) || std::abs(x(2) - r) > options_.start_contact_height ||
      !table::OnSurface(x(0), x(1), options_.contact_margin)) {
    return std::nullopt;
  }
  // The contact was after the frame before the first view (the camera's frame period).
  Junction contact;
  contact.t = t_first - (first[1].t - first[0].t);
  contact.point = {x(0), x(1), r};
  contact.on_plane = true;
  guess.start = contact;
  auto fit = FitStroke(observations, guess, options_.fit);
  if (!Holds(fit, max_rms)) return std::nullopt;
  return fit;
}

std::optional<Stroke> MonocularSmoother::FitRun(
    std::span<const std::vector<BearingObservation>> observations, const Stroke& guess, size_t i,
    size_t j, const LeadIn* lead, const std::optional<Junction>& start) const {
  int views = 0;
  bool has_short = false;
  for (size_t k = i; k < j; ++k) {
    const int size = static_cast<int>(observations[k].size());
    views += size;
    has_short = has_short || size < options_.min_piece_views;
  }
  // Alone, a piece needs many views unless led in (as a window of one).
  if (j - i == 1 && !lead && views < std::max(options_.min_piece_views, options_.min_lone_views)) {
    return std::nullopt;
  }
  Stroke part;
  part.pieces.assign(guess.pieces.begin() + i, guess.pieces.begin() + j);
  part.junctions.assign(guess.junctions.begin() + i, guess.junctions.begin() + (j - 1));
  if (lead) part.start = start;
  std::optional<Stroke> fit = FitStroke(observations.subspan(i, j - i), part, options_.fit, lead);
  const double max_rms = has_short && j - i > 1 ? options_.max_fit_rms_short : options_.max_fit_rms;
  if (!Holds(fit, max_rms)) return std::nullopt;
  return fit;
}

void MonocularSmoother::Apply(const Stroke& stroke, const FlightPiece* lead_in, double t_from,
                              double t_to) {
  for (std::size_t i = 0; i < held_.size(); ++i) {
    FrameSetResult& r = held_[i];
    const double t = ToSeconds(r.t);
    if (t < t_from - 1e-9 || t > t_to + 1e-9 || (lead_in && t <= t_from + 1e-9)) continue;
    placed_[i] = 1;
    const FlightModel& m = options_.fit.model;
    const Vector6d x = lead_in && stroke.start && t < stroke.start->t
                           ? PieceStateAt(*lead_in, t, m, options_.fit.max_step)
                           : StrokeStateAt(stroke, t, m, options_.fit.max_step);
    if (r.state) {
      r.state->position = x.head<3>();
      r.state->velocity = x.tail<3>();
    }
    if (r.measurement) r.measurement->position = x.head<3>();
  }
}

void MonocularSmoother::Continue(const FlightPiece& from, double t_first, double t_last) {
  const Eigen::Vector3d c = camera_.Center();
  for (FrameSetResult& r : held_) {
    const double t = ToSeconds(r.t);
    if (t < t_first - 1e-9 || t > t_last + 1e-9 || !r.measurement) continue;
    const std::optional<View> view = ViewOf(r);
    if (!view) continue;
    const Vector6d x = PieceStateAt(from, t, options_.fit.model, options_.fit.max_step);
    const Eigen::Vector3d p = c + (x.head<3>() - c).norm() * view->bearing.direction;
    r.measurement->position = p;
    if (r.state) r.state->position = p, r.state->velocity = x.tail<3>();
  }
}

void MonocularSmoother::BreakChain(const Piece& rest) {
  pending_bend_ = false;
  FitWindow(false);
  if (!rest.empty()) {
    if (lead_in_ && rest.front().t - lead_in_->after_t <= options_.max_gap_s) {
      Continue(lead_in_->piece, rest.front().t, rest.back().t);
    } else {
      orphans_.push_back(rest);  // the next window may reach back to it
    }
  }
  lead_in_.reset();
  window_.clear();
  junctions_.clear();
}

void MonocularSmoother::Unmeasure(double t) {
  for (FrameSetResult& r : held_) {
    if (std::abs(ToSeconds(r.t) - t) < 1e-9) ClearMeasurement(&r);
  }
}

std::vector<FrameSetResult> MonocularSmoother::Release(double before_t) {
  std::vector<FrameSetResult> out;
  while (!held_.empty() && ToSeconds(held_.front().t) < before_t - 1e-9) {
    if (!placed_.front() && !options_.unplaced_rows_measured && held_.front().measurement) {
      ClearMeasurement(&held_.front());
    }
    out.push_back(std::move(held_.front()));
    held_.pop_front();
    placed_.pop_front();
  }
  return out;
}

}  // namespace p4::track
