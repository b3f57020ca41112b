// Tracking the ball through time (paper §3.3): the Kalman filter predicts each time-stamp,
// corrects with the triangulated measurement when it passes a gate, and fills time-stamps
// without one with its prediction. The paper's heuristics, done better:
// - table bounce: the prediction reflects at the table (z = ball radius inside the outline) at
//   the exact crossing time with a restitution, instead of flipping vz after the fact;
// - the net (beyond the paper): a predicted path that meets it stops there, its velocity then
//   known only loosely (net_model);
// - hit (and any sudden change): a measurement far from the prediction is gated out; the track
//   restarts from it at once when it is a sound multi-camera measurement, or after a second one
//   that agrees with it, with the velocity they imply;
// - a track that does not fall as a ball can (fall_check.h) ends: it is not the ball in play.
// Time: int64 ns from the caller (the frames' time-stamps), never a constant step. Pure.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "p4/core/time.h"
#include "p4/track/fall_check.h"
#include "p4/track/flight_model.h"
#include "p4/track/kalman_filter.h"
#include "p4/track/rts_smoother.h"

namespace p4::track {

// A 3D measurement of the ball centre, world frame, metres.
struct Measurement {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity() * 1e-6;  // m^2
  int cameras = 0;           // views that agreed on it (1 = depth from the ball's diameter)
  double residual_px = 0.0;  // mean reprojection error
};

struct TrackedState {
  TimeNs t = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  bool measured = false;  // a measurement corrected this time-stamp
  int cameras = 0;
  double residual_px = 0.0;
  // Placed on a short flight between two contacts (FrameSetTracker::BetweenContacts): that
  // flight judged it; FlightCheck, whose sides are the flights before and after, does not.
  bool between_contacts = false;
};

struct TrackerOptions {
  KalmanOptions kalman;
  double gate_chi2 = 30.0;    // squared Mahalanobis distance that a measurement must pass
  double max_coast_s = 0.15;  // longest prediction without measurements before the track ends
  // Whether a measurement of one camera (Measurement::cameras 1) counts for max_coast_s. Off in a
  // rig of several cameras: a lone view corrects the filter across its ray, but views of one
  // camera alone cannot hold a track whose depth grows loose (FrameSetTracker).
  bool one_view_holds_track = true;
  double max_speed = 45.0;   // m/s; a restart implying more is refused
  bool bounce_model = true;  // reflect at the table in the prediction
  double bounce_restitution = 0.88;
  double bounce_friction = 0.25;
  // The net in the prediction: a path whose ball meets the net (its centre within ball_radius of
  // the net's plane, below the top of the net plus the radius, between the posts, above the
  // table) is stopped there, and what it does next is not known (it drops, rolls over the tape
  // or comes back): its velocity across the net keeps net_speed_kept of what it was, known to
  // net_speed_sigma of it (at least 1 m/s), the other two axes half theirs, known to
  // net_side_sigma. The measurements after the net then pass the gate; without it the filter
  // coasted on through the net and refused them.
  bool net_model = true;
  double net_speed_kept = 0.25;
  double net_speed_sigma = 0.6;
  double net_side_sigma = 1.5;  // m/s
  double ball_radius = 0.02;
  double init_velocity_sigma = 3.0;  // m/s, of a velocity from two measurements
  double sound_residual_px = 2.0;    // a multi-camera measurement this consistent may restart
  // A measurement the gate refuses restarts the track (at once when sound, else with a second
  // that agrees). Off: it is left out, and the caller starts new tracks (TrackInitiator).
  bool restart_on_refusal = true;
  // A ball in flight falls (fall_check.h): a track whose measurements over the last
  // fall.window_s do not fall as a ball can is not the ball in play (a hand, a shirt, a shoe, a
  // ball held or at rest) and ends. fall.window_s 0: never (and never with the paper's filter).
  FallCheckOptions fall;
  // The filter's steps kept for a smoother (history()): those of the last history_s. 0: none.
  double history_s = 0.0;

  bool IsValid(std::string* error) const;
};

// The ball's physics as the filter and its table bounce take it (gravity, drag, radius,
// restitution, friction): for the stages after the tracker that carry flights of their own.
FlightModel FlightModelOf(const TrackerOptions& options);

class BallTracker {
 public:
  explicit BallTracker(const TrackerOptions& options = {});

  // One time-stamp (strictly increasing). Returns the ball state at t while a track exists.
  std::optional<TrackedState> Step(TimeNs t, const std::optional<Measurement>& measurement);

  // Where the filter expects the ball at t (> last time-stamp), without changing the track.
  std::optional<Eigen::Vector3d> PredictPosition(TimeNs t) const;
  // The same with the position's covariance (m^2).
  std::optional<std::pair<Eigen::Vector3d, Eigen::Matrix3d>> Predict(TimeNs t) const;
  // The predicted velocity at t (m/s, world frame), with a track.
  std::optional<Eigen::Vector3d> PredictVelocity(TimeNs t) const;

  // The filter's steps of the last history_s, oldest first (rts_smoother.h): each time-stamp
  // the track went through, a start at each (re)start.
  const std::vector<FilterStep>& history() const { return history_; }

  bool tracking() const { return tracking_; }
  // The track ended because it did not fall as a ball can (TrackerOptions::fall): what it followed
  // was not the ball.
  bool ended_not_falling() const { return ended_not_falling_; }
  // The measurements the track took over the last fall.window_s (oldest first).
  const std::vector<FallPoint>& recent() const { return recent_; }
  int restarts() const { return restarts_; }

 private:
  // Predicts the filter to dt ahead, with the table bounce and the net.
  static void PredictWithBounce(KalmanFilter* filter, double dt, const TrackerOptions& options);
  // Predicts the filter to dt ahead, with the table bounce only.
  static void PredictWithTable(KalmanFilter* filter, double dt, const TrackerOptions& options);
  // A copy of the filter predicted to t (with the table bounce and the net), with a track.
  std::optional<KalmanFilter> PredictedFilter(TimeNs t) const;
  // A new track from a measurement and a velocity; Began() does the bookkeeping of any start.
  struct Velocity {
    Eigen::Vector3d mean;
    Eigen::Matrix3d covariance;
  };
  void Start(TimeNs t, const Measurement& m, const Velocity& velocity);
  void Began(TimeNs t);
  // Keeps the step to t in the history: from the prior given (nullptr: a start).
  void Record(TimeNs t, const KalmanFilter* prior, double innovation_chi2 = 0.0);
  // The velocity from the measurement kept in pending_ to m, if recent (50 ms) and plausible,
  // with the covariance of the difference: a one-camera pair knows little along the rays.
  std::optional<Velocity> PendingVelocity(TimeNs t, const Measurement& m) const;

  TrackerOptions options_;
  KalmanFilter filter_;
  bool tracking_ = false;
  bool ended_not_falling_ = false;
  TimeNs last_t_ = 0;
  TimeNs last_update_t_ = 0;
  TimeNs last_fix_t_ = 0;  // the last measurement that holds the track (one_view_holds_track)
  Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();  // filtered, at last_update_t_
  std::optional<std::pair<TimeNs, Measurement>> pending_;    // a measurement the gate refused
  std::vector<FallPoint> recent_;  // the measurements the filter took over fall.window_s
  int restarts_ = 0;
  std::vector<FilterStep> history_;  // a few dozen steps: trimmed at the front
};

}  // namespace p4::track
