// The ball's flight seen from one camera, fitted over a whole stroke (beyond the paper, whose
// one-camera depth from the diameter is "error-prone", §3.2).
//
// A stroke is the flight from one hit to the next: pieces of free flight joined where the ball
// touched a plane (the table top at z = ball radius, or the floor). Each piece moves under
// gravity, air drag (-k |v| v, the ball's known k/m) and a Magnus acceleration b x v whose vector
// b (the spin times k_m/m) is the piece's own: the bounce changes the spin. A junction is a time
// and a point that the piece before and the piece after both pass; at a bounce the point lies on
// the plane. The stroke before (its last piece, already fitted) may lead in: the ball leaves the
// racket where it arrived, so the first piece starts where that one ended.
//
// What fixes the depth along the camera's rays: the bearings give each piece's shape up to its
// distance; a bounce sits where a ray meets a known plane, which anchors both pieces it joins;
// the lead-in carries the last anchor across the hit; at a bounce the velocity after follows from
// the velocity before (restitution and friction, give or take the spin); the diameters (noisy, ~3 %
// of the distance per frame) and gravity weigh in everywhere. Least squares over all pieces and
// contacts at once (Ceres, automatic derivatives, one pass of the integration per piece; Huber
// loss on every bearing, Cauchy loss on every diameter: neither a stray detection nor a ball
// merged with a player's arm may pull the flight).
//
// World frame of DESIGN.md (z up), metres, seconds, radians. Pure.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/track/flight_model.h"
#include "p4/track/kalman_filter.h"

namespace p4::track {

// One frame's view of the ball from a camera.
struct BearingObservation {
  double t = 0.0;                                        // s
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // camera centre
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit ray to the ball
  double angle_sigma = 1e-3;                             // rad (pixel noise / focal length)
  double distance = 0.0;                                 // from the diameter (0: none)
  double distance_sigma = 1.0;                           // m
};

// A piece of free flight: its state at t0 and its Magnus vector.
struct FlightPiece {
  double t0 = 0.0;                                   // s
  Vector6d state = Vector6d::Zero();                 // (x, y, z, vx, vy, vz) at t0
  Eigen::Vector3d magnus = Eigen::Vector3d::Zero();  // b of a = b x v, 1/s
  // For the fit: a service toss, which the laws (2.6.2) want "near vertically upwards, without
  // imparting spin".
  bool toss = false;
};

// Where two pieces meet: a time and a point both pass. On a plane (a bounce: the ball centre's
// height is known, e.g. the table's ball radius) point.z() is held at its given value.
struct Junction {
  double t = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  bool on_plane = false;
};

struct Stroke {
  std::vector<FlightPiece> pieces;
  std::vector<Junction> junctions;  // junctions[i] joins pieces[i] and pieces[i + 1]
  // With a lead-in: where the lead-in piece meets pieces[0]; without one, a contact on a plane
  // that pieces[0] left (FitStroke).
  std::optional<Junction> start;
  double rms_bearing = 0.0;  // bearing residuals of the fit, in sigmas
  // Per piece, the median over its views with a diameter of |fitted distance / (the piece's
  // scale x the diameter's) - 1|; the largest of them. The losses let stray diameters go, but a
  // piece most of them disagree with was placed where the ball was not (slid along its rays, where
  // only the bearings hold it). 0: no diameters.
  double median_distance_error = 0.0;
  double distance_scale = 1.0;  // the fitted common scale of the diameters' distances
  // The common scale or a piece's own came to rest on its bound (3 sigmas,
  // StrokeFitOptions::distance_scale_sigma): only a scale that far off reconciles the diameters
  // with the bearings and the anchors, and the distance errors above, measured with that scale,
  // do not show it. Such a fit is wrong (a lead-in placed off, a bounce misjudged).
  bool scale_at_bound = false;
};

// The last piece of the stroke before, already fitted and held fixed: pieces[0] starts where it
// ends, at a time between `after_t` (its last view) and pieces[0]'s first view.
struct LeadIn {
  FlightPiece piece;
  double after_t = 0.0;
  double sigma = 0.02;  // m, how well the lead-in piece knows its end
};

struct StrokeFitOptions {
  FlightModel model;               // gravity, drag, ball radius
  double magnus_sigma = 1.0;       // 1/s, prior on each component of b (550 rad/s of spin ~ 1.0)
  double toss_magnus_sigma = 0.1;  // 1/s, the same for a toss
  double toss_horizontal_sigma = 0.5;  // m/s, prior on a toss's horizontal velocity
  double contact_sigma = 0.002;        // m: how closely both pieces pass their contact point
  // The diameters share a bias the per-view noise does not average out: a blurred ball reads
  // short (its streak's sides are covered for less of the exposure), a shaded one short or long
  // with the lighting. Their distances are fitted times one scale per fit, ~ N(1, sigma^2),
  // where a bounce on a known plane or the lead-in anchors the fit (in free flight gravity's
  // pull in the image alone would fix it, but the spin's pull confounds it); it stays within 3
  // sigmas. 0: the scale is 1.
  double distance_scale_sigma = 0.1;
  // ...and each piece's scale about that common one, ~ N(common, sigma^2), where the fit is
  // anchored: the bias changes with the ball's speed (a serve toss at 2-3 m/s is sharp, the
  // drive after it blurred over a ball's diameter in a 4 ms exposure) and with the light along the
  // flight. A toss without spin is placed by gravity's pull in the image, a piece before a
  // bounce by the table. Chosen on mono tuning scenes 1-12 (0.03 and 0.05 tried;
  // docs/DECISIONS.md). 0: one scale for all.
  double piece_scale_sigma = 0.05;
  // The velocity after a bounce vs the bounce map of the velocity before (model.restitution,
  // model.friction): what spin can change, m/s.
  double bounce_sigma_horizontal = 0.7;
  double bounce_sigma_vertical = 0.6;
  double huber_sigmas = 3.0;          // bearing residuals beyond this count linearly
  double distance_loss_sigmas = 1.0;  // diameters' distances beyond this count ~logarithmically
  double max_step = 0.004;            // s, integration step (midpoint rule: < 0.1 mm at 4 ms)
  int max_iterations = 60;

  bool IsValid(std::string* error) const;
};

// State (x, y, z, vx, vy, vz) of a piece at time t (before or after t0), by integrating its
// motion in steps of at most max_step.
Vector6d PieceStateAt(const FlightPiece& piece, double t, const FlightModel& model,
                      double max_step = 0.004);

// The state at t of the piece that covers t: piece i up to junction i, then piece i + 1.
Vector6d StrokeStateAt(const Stroke& stroke, double t, const FlightModel& model,
                       double max_step = 0.004);

// A starting point for a piece: the linear least-squares fit of p(t) = p0 + v0 dt + a dt^2 / 2
// (dt = t - observations[0].t, a free) to the bearings and distances, weighted by their sigmas.
// Returns the piece at t0 = the middle observation's time (the fit then integrates half as far)
// with no spin. Precondition: >= 3 observations.
FlightPiece QuadraticPiece(std::span<const BearingObservation> observations);

// Preconditions: observations.size() == guess.pieces.size() >= 1, guess.junctions.size() ==
// pieces - 1, each piece's observations in increasing time with at least 3 of them, and the
// pieces in time order. guess: a starting point (t0 of each piece is kept as given; guess.start
// is used with a lead-in when set). Without a lead-in, guess.start on a plane (point.z() its
// height) says the first piece left a contact with that plane at guess.start->t or later, before
// its first view (a bounce whose arrival no view saw): it anchors the fit as a bounce between
// pieces does; the contact found is the result's start. nullopt when the solver fails or the
// solution is not finite.
std::optional<Stroke> FitStroke(std::span<const std::vector<BearingObservation>> observations,
                                const Stroke& guess, const StrokeFitOptions& options,
                                const LeadIn* lead_in = nullptr);

}  // namespace p4::track
