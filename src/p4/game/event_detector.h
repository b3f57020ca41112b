// Events of play from the ball's 3D track (paper §4: "every bounce is interpreted"): the track is
// cut into ballistic pieces where a measured point leaves the current piece's fit and the next
// ones agree among themselves; each cut is classified by where the two pieces meet and how the
// velocity changes — a table bounce (vz flips near the surface, over the table), the floor, the
// net (near the net plane, below its top), or a hit (anything else that changes the velocity by
// more than `min_hit_dv`). Within a piece, passing the net plane below its top is a net touch and
// falling through the surface's plane outside the table is "out".
//
// Event times come from the pieces' fits where they meet, not from frame times. Frames: world
// metres (DESIGN.md). Pure and streaming: points in, events out a few frames later.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "p4/core/table.h"
#include "p4/game/event.h"

namespace p4::game {

struct EventDetectorOptions {
  double break_m = 0.015;   // a point this far from the piece's prediction may start a new piece
  int confirm_points = 3;   // points after a cut that must agree with each other
  double max_gap_s = 0.12;  // longer without a point ends the piece (no event)
  double window_s = 0.2;    // a piece's fit uses its last this much
  int min_free_fit = 8;     // below this many points the fit's acceleration is gravity alone
  double gravity = 9.81;    // m/s^2
  double ball_radius = table::kBallRadius;
  double bounce_max_z = 0.08;  // m, ball centre where the pieces meet, for a table bounce
  double bounce_min_vz = 0.2;  // m/s, |vz| before and after a bounce at least
  double table_margin = 0.02;  // m, the outline grown by this for a bounce (edge balls)
  double net_reach = 0.08;     // m, |x| of a cut that can be the net
  double min_hit_dv = 1.5;     // m/s, velocity change of a hit
  // A piece that ends (the ball lost) is followed this far ahead for an "out".
  double max_extrapolation_s = 0.08;

  bool IsValid(std::string* error) const;
};

class EventDetector {
 public:
  explicit EventDetector(const EventDetectorOptions& options = {});

  // A measured ball centre at t (seconds, increasing). Returns the events it decides, in time
  // order (their times are earlier than t).
  std::vector<Event> Push(double t, const Eigen::Vector3d& position);
  // The end of the stream: events a last short piece still holds.
  std::vector<Event> Flush();

 private:
  struct Sample {
    double t;
    Eigen::Vector3d p;
  };
  // p(t) = a + b (t - t0) + c (t - t0)^2 per axis.
  struct Fit {
    double t0 = 0.0;
    int samples = 0;  // points the fit rests on
    Eigen::Vector3d a, b, c;
    Eigen::Vector3d At(double t) const;
    Eigen::Vector3d VelocityAt(double t) const;
  };
  // The last window_s of the samples (with `window`) or all of them.
  Fit FitSamples(std::span<const Sample> samples, bool window) const;
  void CheckCrossings(const Sample& from, const Sample& to, std::vector<Event>* out);
  void Cut(std::vector<Event>* out);

  EventDetectorOptions options_;
  std::vector<Sample> piece_;
  std::vector<Sample> pending_;
  bool net_reported_ = false;
  bool out_reported_ = false;
};

}  // namespace p4::game
