// Which 3D candidates are the ball in play: new tracks are confirmed by the ball's motion
// (beyond the paper, whose §3.3 starts the filter from the first measurement).
//
// A lamp, a letter of a banner, a ball-coloured shoe or a spare ball on the floor can agree
// across views (epipolar, size) as well as the ball does; what none of them does is fly. Every
// time-stamp's candidates (all of them, not only the best) extend short chains, tracklets: a
// candidate extends a tracklet when it lies where the tracklet's last two points send the ball
// (gravity and drag, dt from the time-stamps), within a gate of model error plus the
// measurements' own noise. A tracklet is confirmed, and may start the filter's track, once it
// has confirm_points points in a row and has travelled min_travel: the ball in play moves, the
// hall does not. Points older than max_span_s slide out (a static spot never confirms however
// long it stays); a tracklet not extended for max_missed time-stamps ends. A slow ball confirms by
// falling with gravity's curvature instead (a toss near its top).
//
// World frame, metres, seconds (time-stamps in ns from the caller). Pure.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/core/time.h"
#include "p4/track/ball_tracker.h"

namespace p4::track {

struct TrackInitiatorOptions {
  int confirm_points = 4;  // points in a row that confirm a tracklet...
  // ...or at least min_confirm_points spanning confirm_span_s, each seen as a blur streak in
  // every view (it moved two diameters or more within one exposure: not a hand, not a lamp).
  // Cameras of 30 fps or slower see a flight between bounces in few frames, and 3 of them span
  // as long as 6 at 60 fps.
  int min_confirm_points = 3;
  double confirm_span_s = 0.075;
  double min_travel = 0.10;  // m between its first and last point (2.5 ball diameters)...
  // ...at this mean speed at least (m/s): slower, a hand or a shirt moves as far; a slow ball
  // (the top of a toss) confirms by its fall below.
  double min_travel_speed = 1.5;
  // ...and stands out of its two ends' noise by this many sigmas along the noise axes (one
  // camera's depth from the diameter alone wanders by more than min_travel).
  double min_travel_sigmas = 4.0;
  // A slow ball (a serve toss near its top) travels less, but falls as nothing else in the hall
  // does: a tracklet spanning fall_span_s whose points all fit one flight (fit_tolerance, as the
  // newest must), whose heights fit a parabola with gravity's curvature (within fall_tolerance
  // of g, residuals within 2 sigmas of the measurements) and has fall_points points at least is
  // confirmed too (the heights of a shirt's edge, its pieces jumping sideways, may rise and fall
  // with g's curvature by chance): a parabola has 3 parameters, and through 4 points of a hand
  // or a shirt's edge (a 25 fps camera's 0.1 s) one with g's curvature is found by chance.
  double fall_span_s = 0.1;
  double fall_tolerance = 0.3;
  int fall_points = 6;
  // ...and the heights must be known well enough to show it: the fitted curvature's sigma (from
  // the heights' sigma) at most this (m/s^2; g/2 is 4.9). One camera's heights, known only to
  // centimetres along its ray, cannot confirm by falling.
  double fall_max_curvature_sigma = 3.0;
  // A serve's toss rises slowly from the first (a legal toss leaves the hand at 1.8 m/s or more
  // and gravity takes 0.4 m/s off it in 0.04 s: its first 4 points at 25 fps average 1.2-1.4
  // m/s, under min_travel_speed) and nearly straight up: a tracklet spanning fall_span_s that
  // rose min_travel with its horizontal travel within toss_max_lean of its rise (27 degrees off
  // the vertical) is confirmed too; its newest points must still fit one flight (fit_tolerance).
  // Over 4 points at 25 fps that fit does not tell gravity's pull from a steady lift (4 mm RMS
  // apart): a hand lifting something of the ball's colour and size 10 cm straight up in 0.1 s is
  // confirmed as well, and its track ends after slow_window_s (it does not fall). 0: off.
  double toss_max_lean = 0.5;
  // The newest confirm_points must fit one flight (gravity and drag, no spin, no bounce) within
  // this RMS (m) plus fit_sigmas of the measurements: the gate below, from two points, is wide
  // when they are 40 ms apart (a still speck paired with a moving one flies along a ray).
  double fit_tolerance = 0.01;
  double fit_sigmas = 1.5;
  double gate = 0.03;        // m of model error (spin, a bounce's start) in the prediction...
  double gate_sigmas = 4.0;  // ...plus this many sigmas of the measurements and the velocity
  // A tracklet not extended for more than max_missed time-stamps ends (the ball is seen in
  // almost every frame; a flicker of the hall is not), and one not extended for max_gap_s, or
  // for max_missed + 1.5 periods of the time-stamps where that is longer (30 fps or slower).
  // Whose last point is of one view (one camera: placed along its ray by its diameter, to
  // centimetres) waits max_missed_one_view: the gate grows with the wait, and through a wider
  // one a point that far along the ray passes.
  double max_gap_s = 0.07;
  int max_missed = 2;
  int max_missed_one_view = 1;
  double max_span_s = 0.25;  // points older than this slide out
  double max_speed = 45.0;   // m/s; a second point farther than this from the first is not it
  // A tracklet whose last window_s does not fall as a ball can (fall_check.h: a shoe or a shirt
  // moving level at 2-4 m/s; 4 points of a 25 fps camera fit a flight, too few to tell) is not
  // confirmed; FrameSetTracker gives it the tracker's (TrackerOptions::fall).
  FallCheckOptions fall;
  double gravity = 9.81;          // m/s^2
  double drag_per_mass = 0.1407;  // 1/m, as the filter's
  int max_tracklets = 64;         // the youngest are dropped beyond this

  bool IsValid(std::string* error) const;
};

// One 3D candidate of one time-stamp: the measurement and the detections it was made of (the
// caller's indices, handed back when the tracklet is confirmed).
struct TrackletPoint {
  TimeNs t = 0;
  Measurement measurement;
  std::vector<int> detections;
  bool streak =
      false;          // every view of it is a faint blur streak (no disc: it moved in the exposure)
  int64_t stamp = 0;  // set by the initiator: which of its time-stamps
  // Some of its views stood still where others moved, in a camera where standing still says a
  // ball at min_travel_speed flies along its ray (FrameSetTracker): most often a still speck
  // paired with something that moves, whose point flies along the speck's ray as a ball would.
  // Such points count for nothing toward a tracklet's confirmation by its travel (a slow ball,
  // still anywhere, confirms by its toss or its fall as before).
  bool still_and_moving = false;
  // Every view of it is a faint streak that does not show the ball's colour
  // (FrameSetOptions::off_colour_residual): such points are not counted among the points a
  // confirmation needs (they stay in its fits).
  bool off_colour = false;
};

struct Tracklet {
  std::vector<TrackletPoint> points;  // oldest first
  // Of a confirmed tracklet: its first point of the one flight (gravity and drag, no contact)
  // that its newest points fit, as far back as they still fit it. Its gate may have taken the
  // ball through a hit: the points before are the flight the racket ended.
  std::size_t flight_start = 0;
  // Its points were what a track followed until it ended for not falling as a ball can
  // (TrackInitiator::NotTheBall): it is confirmed only once its fall is judged a ball's.
  bool not_ball = false;
};

class TrackInitiator {
 public:
  explicit TrackInitiator(const TrackInitiatorOptions& options = {});

  // One time-stamp's candidates (strictly increasing t; no two share a detection, but for a
  // faint streak's, whose size cannot tell which pairing is the ball). Returns the
  // tracklet confirmed at t, if any (the longest when several); it is handed over and no longer
  // kept. Its last point is one of `candidates`.
  std::optional<Tracklet> Push(TimeNs t, std::span<const TrackletPoint> candidates);

  // At the end of the recording: the longest tracklet that ended at the last time-stamp pushed
  // and would have confirmed but for the points that never came (min_confirm_points, each of two
  // views or more, its travel and one flight as Push asks); it is handed over.
  std::optional<Tracklet> Finish();

  // A track ended for not falling as a ball can, after taking `taken` (its last measurements):
  // the tracklets with a point within `radius` (m) of one of them at its time follow the same
  // thing, and are confirmed only once their fall is judged (Tracklet::not_ball).
  void NotTheBall(std::span<const FallPoint> taken, double radius);

  void Clear() { tracklets_.clear(); }
  int size() const { return static_cast<int>(tracklets_.size()); }

 private:
  // Where the tracklet sends the ball at t and how far from it a point may lie: an ellipsoid of
  // semi-axes `radii` (m) along the columns of `axes` (a sphere for views of several cameras).
  struct Gate {
    Eigen::Vector3d centre;
    Eigen::Matrix3d axes;
    Eigen::Vector3d radii;
  };
  Gate Predict(const Tracklet& tracklet, TimeNs t) const;
  // `at_end`: the recording ended (Finish).
  bool Confirmed(const Tracklet& tracklet, bool at_end = false) const;
  // The longest tracklet ending at t that is Confirmed(at_end), taken out with its flight_start
  // set, and with the tracklets that share a point with it (the same ball, a step behind).
  std::optional<Tracklet> TakeConfirmed(TimeNs t, bool at_end);
  // The points' distances from the best flight through them, in units of fit_tolerance plus
  // fit_sigmas of their noise; whether they fit it (RMS within 1).
  Eigen::VectorXd Residuals(std::span<const TrackletPoint> points) const;
  bool FitsOneFlight(std::span<const TrackletPoint> points) const;
  // The fall of the points' last fall.window_s (fall_check.h).
  FallFit Fall(std::span<const TrackletPoint> points) const;
  // Tracklet::flight_start of a confirmed tracklet.
  std::size_t FlightStart(const Tracklet& tracklet) const;

  TrackInitiatorOptions options_;
  std::vector<Tracklet> tracklets_;
  int64_t stamps_ = 0;  // time-stamps pushed
  std::optional<TimeNs> last_t_;
  TimeNs period_ = 0;  // the shortest interval between two pushes (0: fewer than two)
};

}  // namespace p4::track
