// Rows that leave the ball's flight (beyond the paper): each measured row of the track is judged
// against the flight of the measured rows on either side of it, held until the rows after it are
// in. Each side's nearest rows (up to side_rows, within horizon_s) give a position and a velocity
// under gravity and drag (FlightModel), carried to the judged row's time, through a table bounce
// either way (restitution and friction; inverted going back). A row farther than
// offset_m + model_accel h^2 / 2 from every side that can judge (h: the side's nearest row's time
// away) is not the ball: a wrong pair of views, a shirt or an arm taken for the ball for one
// time-stamp. Its measurement is dropped and its state moved onto the nearer side's flight; if no
// measured row follows it in its track (the states run on without a gap), or none comes before it,
// its state goes too, with the track's predictions from its last measurement to it and on to the
// track's end (or from the track's start to its next measurement): rows are the ball seen or the
// gaps between its sightings (as FrameSetTracker's dropped coasts).
//
// A side can judge when it has min_side_rows rows and, with 3 or more, they fit one flight within
// side_rms_m (a side that holds a hit or a bounce between its rows does not judge). A row is kept
// when one side agrees with it: at a hit or a bounce the ball follows the flight of one side up to
// that moment and of the other after it. The worst row goes first, then the rows around it are
// judged again without it; a row is final only when every row within horizon_s of it has both
// sides in (2 horizon_s after it).
//
// World frame of DESIGN.md (z up, table top z = 0), metres, seconds; time-stamps int64 ns. Pure.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "p4/track/flight_model.h"
#include "p4/track/frame_set_tracker.h"

namespace p4::track {

struct FlightCheckOptions {
  double horizon_s = 0.25;  // a side's rows lie within this time of the judged row
  int side_rows = 3;        // rows fitted per side, the nearest
  int min_side_rows = 2;
  double side_rms_m = 0.02;  // a side of 3+ rows fitting one flight worse than this does not judge
  // Distance from a side's flight that a row may always have (its own noise and a webcam's blur:
  // the run's false rows are those 50 mm from the ball).
  double offset_m = 0.06;
  // What the flight model may miss (spin: the Magnus acceleration reaches 10-20 m/s^2), m/s^2.
  double model_accel = 30.0;
  FlightModel model;

  bool IsValid(std::string* error) const;
};

class FlightCheck {
 public:
  // Precondition: options valid.
  explicit FlightCheck(const FlightCheckOptions& options);

  // Takes a final result (time-stamps increasing; ResultHold's output); returns the results now
  // judged, oldest first.
  std::vector<FrameSetResult> Push(FrameSetResult result);
  // Every held result, judged with the sides there are.
  std::vector<FrameSetResult> Flush();

  int dropped() const { return dropped_; }  // rows whose measurement left the flight

 private:
  struct Held {
    FrameSetResult result;
    bool judged = false;  // both of its sides are in: it may be dropped
    double score = 0.0;   // distance / allowed of its nearest side (0: no side judges it)
    Vector6d on_flight = Vector6d::Zero();  // the nearer judging side's state at its time
  };
  struct Row {
    TimeNs t;
    Eigen::Vector3d position;
  };
  // Side rows of held_[i] (direction -1: before, +1: after), nearest first; without the rows
  // under suspicion (score > 1) when skip_suspects.
  std::vector<Row> SideRows(int i, int direction, bool skip_suspects) const;
  // held_[i]'s score and flight from its sides (it must be measured).
  void Score(int i, bool skip_suspects);
  // Scores the rows whose sides are in, then drops the worst row over 1 among those whose
  // neighbours' sides are in too, again and again (all: every row, at the end).
  void Judge(TimeNs newest, bool all);
  // held_[i] lost its measurement: without a measured row on one side of it in its run of
  // states, the unmeasured states from the measured row on the other side to the run's end go.
  void DropUnconfirmedStates(int i);

  FlightCheckOptions options_;
  TimeNs horizon_;
  std::deque<Row> past_;  // measured rows already out, within horizon_ of the oldest held
  std::deque<Held> held_;
  // A measured row has been released since the last released row without a state.
  bool released_run_measured_ = false;
  int dropped_ = 0;
};

}  // namespace p4::track
