// One camera's track refined over its flight between table contacts (beyond the paper, whose
// one-camera depth from the ball's diameter is "error-prone", §3.2).
//
// The Kalman filter gives each time-stamp at once, but from one camera it knows the depth along
// the ray only from the diameter (~3 % of the distance per frame, and biased where the ball
// overlaps a player). This stage holds the tracker's time-stamps back until the ball's next table
// bounce, fits the flight since the last one (stroke_fit.h: bearings, diameters, gravity, drag,
// spin, the table under each bounce, the ball's continuity through hits) and hands them on with
// the fit's positions and velocities. The delay is one bounce to the next (median ~0.4 s).
//
// Pieces and junctions: in flight the ball's image path is smooth; a bounce or a hit bends it.
// Each view is predicted by a quadratic in time through the piece's last `window` views (in the
// camera's undistorted pixels); `kink_views` views in a row off by more than `kink_px`, the last
// by `bend_px`, end the piece (one or two are strays and are left out). The bend is a table bounce
// when the ball goes down before and up after, keeps its speed across the ray in sign and mostly in
// size, and the ray there meets the table top (z = ball radius) inside its outline at a distance
// that the diameters on both sides agree with; the floor likewise. Any other bend (a hit, the net)
// is a free junction: the ball leaves it where it arrived. A bounce closes the window: the pieces
// up to it are final, and the last of them leads into the next window. A gap in the views
// (max_gap_s) or a piece too short to fit breaks the chain.
//
// Input: the FrameSetTracker's results in time order, for a rig of one camera. World frame,
// metres, seconds. Pure: time comes with the results.
#pragma once

#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/geometry/camera.h"
#include "p4/track/frame_set_tracker.h"
#include "p4/track/stroke_fit.h"

namespace p4::track {

struct MonocularSmootherOptions {
  StrokeFitOptions fit;
  double pixel_sigma = 0.5;      // centroid noise, px
  double diameter_sigma = 0.35;  // diameter noise, px
  int window = 8;                // views of the quadratic that predicts the next one
  double kink_px = 2.5;          // a view this far from the prediction is off the piece
  double adopt_px = 2.5;    // a candidate the tracker did not take, this near the path, is the ball
  int kink_views = 3;       // views off in a row that end the piece, the last by bend_px...
  double bend_px = 10.0;    // ...(or twice as many views off by less)
  int min_piece_views = 6;  // views after a bend that decide whether it is a bounce
  int min_fit_views = 3;    // a shorter piece breaks the chain (the filter's rows stay)
  int min_lone_views = 12;  // a window with no bounce, hit or lead-in to hold it
  double max_gap_s = 0.1;   // views farther apart break the chain
  // Where a window is cut into runs, a run is led in by the one before across at most this many
  // of its frame periods (more missed frames may hide another bend).
  double lead_max_gap_frames = 4.5;
  double max_window_s = 2.5;     // a longer window without a bounce is handed on anyway
  double contact_margin = 0.05;  // m beyond the table's outline that still counts as on it
  // A chain's first piece whose first view lies this near the table top (m, rising, as the
  // flight fitted alone places it: no contact, no toss; the diameters' bias may place it a few
  // per cent of the distance off) left the table just before it (FitFromTable; 0: never).
  double start_contact_height = 0.08;
  double contact_depth_agree = 0.6;  // m: the diameters' distance vs the contact's, at most...
  double contact_depth_agree_share = 0.25;  // ...or this share of the contact's distance
  // A bounce keeps the horizontal velocity across the ray in sign and mostly in size (friction
  // takes some, topspin may add some); a hit or the net do not. Judged when either side is faster
  // than bounce_min_speed.
  double bounce_min_speed_ratio = 0.4;
  double bounce_max_speed_ratio = 1.6;
  double bounce_min_speed = 1.0;  // m/s
  // A change within the table's friction (mu (1 + e) |vz|) plus this (m/s) passes whatever the
  // ratio.
  double bounce_speed_slack = 0.5;
  // Down and up are judged across the ray where the vertical has this much across it (the sine
  // of the ray's angle to the vertical), else in 3D.
  double bounce_min_up_across = 0.3;
  double max_fit_rms = 3.0;        // bearing residuals (sigmas) above which a fit is not used
  double max_fit_rms_short = 1.0;  // the same for a window with a piece of < min_piece_views
  double merge_rms = 1.2;          // two pieces that one flight fits this well (sigmas) are one
  // A fit with a piece whose distances most of its diameters disagree with by more than this
  // share (the median; the fit's common scale applied) is not used: the piece slid along its
  // rays, where only the bearings hold it (a short piece after a hit). The diameters' own noise
  // is a few per cent; their bias along a flight (shading, blur) some more.
  double max_distance_error = 0.25;
  // A chain that starts slower than this (m/s, mid-piece) and rising starts with the service
  // toss: fitted without spin.
  double toss_max_speed = 4.0;
  // A row that no fit placed (its window did not hold, a piece too short to fit, the chain cut
  // by a gap) keeps the filter's state, or the distance of the flight next to it (Continue):
  // its depth is the diameters' alone (a few per cent of the distance, ~10 cm at 4 m) or an
  // extrapolation (after a hit in the gap, the flight before it carried on). It stays a row but
  // is no measurement. True: such rows stay measurements (as before 2026-12-05;
  // docs/DECISIONS.md).
  bool unplaced_rows_measured = false;

  bool IsValid(std::string* error) const;
};

class MonocularSmoother {
 public:
  MonocularSmoother(const Camera& camera, const MonocularSmootherOptions& options = {});

  // Takes the next time-stamp's result; returns those now final, in time order.
  std::vector<FrameSetResult> Push(FrameSetResult result);
  // At the end of the input: fits what is open and returns the rest.
  std::vector<FrameSetResult> Flush();

  int windows_fitted() const { return windows_fitted_; }
  int bounces_found() const { return bounces_found_; }

 private:
  struct View {
    double t = 0.0;
    Eigen::Vector2d ideal_px;  // undistorted pixel
    BearingObservation bearing;
  };
  using Piece = std::vector<View>;

  std::optional<View> ViewFrom(const FrameSetResult& result, const Detection& d) const;
  // The view of the detection the tracker accepted.
  std::optional<View> ViewOf(const FrameSetResult& result) const;
  // This time-stamp's view of the ball: the candidate on the open piece's path, which may be one
  // the tracker did not take (it is then marked accepted and the row measured).
  std::optional<View> Adopt(FrameSetResult* result,
                            const std::optional<Eigen::Vector2d>& path) const;
  // The piece's path (undistorted px) at t: the quadratic through its last `window` views;
  // nullopt below 4 views.
  std::optional<Eigen::Vector2d> PathAt(const Piece& piece, double t) const;
  Eigen::Vector2d IdealPixel(const Eigen::Vector2d& pixel) const;  // undistorted, in px
  // Ends the open piece; `next`: the views that begin the next one (empty: the chain breaks).
  void EndPiece(const Piece& next);
  // Judges the bend between the window's last piece and the open one; a bounce closes the window.
  void DecideBend();
  // The junction at the bend: on the plane if it is a bounce, else free.
  Junction JunctionBetween(const Piece& before, const Piece& after) const;
  // Fits the window's pieces (and the open piece when `with_open`) after the lead-in and makes
  // the rows up to the window's last piece final.
  void FitWindow(bool with_open);
  // The window's pieces [i, j) fitted as one run after `lead` (none: alone) meeting it at
  // `start`, when the fit holds; a lone piece needs min_lone_views unless led in.
  std::optional<Stroke> FitRun(std::span<const std::vector<BearingObservation>> observations,
                               const Stroke& guess, size_t i, size_t j, const LeadIn* lead,
                               const std::optional<Junction>& start) const;
  // A chain that starts with no lead-in, its first piece (as `alone`, the window fitted without
  // contact or toss, places it) rising from the table top at its first view
  // (start_contact_height, the outline and contact_margin): the ball left the table in the frame
  // period before, a bounce whose arrival no view saw (behind the net, after a net cord, a gap in
  // the views). The window fitted from that contact (stroke_fit.h: it anchors the diameters'
  // scale as a bounce between pieces does) when that fit holds; else nullopt.
  std::optional<Stroke> FitFromTable(std::span<const std::vector<BearingObservation>> observations,
                                     Stroke guess, const Stroke& alone, double max_rms) const;
  // The fit explains the bearings within max_rms and the diameters (max_distance_error), and no
  // diameters' scale rests on its bound (Stroke::scale_at_bound: a lead-in or a contact placed
  // where the ball was not).
  bool Holds(const std::optional<Stroke>& fit, double max_rms) const;
  void Apply(const Stroke& stroke, const FlightPiece* lead_in, double t_from, double t_to);
  // Views between t_first and t_last that no fit explains: on their rays, at the distance the
  // flight next to them (`from`, before or after) has there (the ball cannot be far from where
  // it was a moment ago). Rows, not measurements (unplaced_rows_measured): that flight may have
  // been hit in the gap.
  void Continue(const FlightPiece& from, double t_first, double t_last);
  // The chain breaks: what is open is fitted; `rest` (views too few to fit) keeps its rays at
  // the distance where the flight before ended (or waits as an orphan); no lead-in, window or
  // junctions remain.
  void BreakChain(const Piece& rest);
  // A view that is no view of the ball's flight (off every piece at a bend): its row is no
  // measurement (the filter's place stays, unless a fit later spans it).
  void Unmeasure(double t);  // the held row at t
  std::vector<FrameSetResult> Release(double before_t);

  Camera camera_;
  MonocularSmootherOptions options_;
  std::deque<FrameSetResult> held_;
  std::deque<char> placed_;          // per held row: a fit placed it (Apply)
  std::vector<Piece> window_;        // finished pieces since the last bounce
  std::vector<Junction> junctions_;  // after each of them (the last: before the open piece)
  Piece piece_;                      // the open piece
  std::vector<View> off_;            // views off the open piece, in a row
  bool pending_bend_ = false;        // the bend before piece_ is not judged yet
  std::optional<LeadIn> lead_in_;    // the fitted piece before the window
  std::vector<Piece> orphans_;       // views too few to fit, waiting for a window after them
  Junction lead_in_junction_;        // where it meets the window's first piece
  int windows_fitted_ = 0;
  int bounces_found_ = 0;
};

}  // namespace p4::track
