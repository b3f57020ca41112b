// `p4track track` as a library call: frame sets from the sources, the per-time-stamp tracker,
// the run's files written as it goes, and a summary. The edge between the pure tracker and the
// files and clocks.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "p4/game/event_detector.h"
#include "p4/game/referee.h"
#include "p4/geometry/rig.h"
#include "p4/io/video_reader.h"
#include "p4/pipeline/frame_set_reader.h"
#include "p4/pipeline/live_sink.h"
#include "p4/segment/color_classes.h"
#include "p4/track/flight_check.h"
#include "p4/track/frame_set_tracker.h"
#include "p4/track/monocular_smoother.h"

namespace p4 {

// The game layer of a run (paper §4): events from the track and the referee's score.
struct GameOptions {
  bool enabled = true;
  game::EventDetectorOptions detector;
  game::RefereeOptions referee;
  std::array<std::string, 2> players{"A", "B"};  // names of A (x < 0) and B (x > 0)

  bool IsValid(std::string* error) const;
};

// Optional parts of a run: a live view, and pacing recorded files at their own frame rate (a
// replay "as live"; live sources are paced by themselves).
struct RunExtras {
  LiveSink* live = nullptr;
  bool realtime = false;
  // A one-camera rig's rows are refined over each stroke (track::MonocularSmoother) before they
  // are written and scored: about one stroke later (the live view is not delayed).
  bool smooth_one_camera = true;
  // A rig of 2+ cameras' measured rows are judged against the ball's flight on either side of
  // them (track::FlightCheck) before they are written and scored: 2 horizon_s later.
  bool check_flight = true;
  track::FlightCheckOptions flight_check;
  // Play video files again and again until stopped (FrameSetReader's loop).
  bool loop = false;
  // Set by another thread (e.g. on Ctrl-C): the run ends after the frame set in hand, its files
  // finished as at the sources' end (held rows written, the last score). May be null.
  const std::atomic<bool>* stop = nullptr;
  // Continue a run that stopped (kill -9, a crash): the run is made again from its start (it is
  // deterministic), the rows already in out_dir checked and kept, the rest appended (RunWriter).
  bool resume = false;
  // Called once for each damaged stretch a source skipped (io/video_reader.h), as it is met.
  std::function<void(const std::string& source, const VideoGap& gap)> on_gap;
  // Called when a live source is lost (it is opened again in the background) and when it is back.
  std::function<void(const std::string& source, const SourceEvent& event)> on_source;
};

struct TrackRunSummary {
  int64_t frame_sets = 0;
  int64_t measured = 0;     // time-stamps with a 3D measurement
  int64_t multi_view = 0;   // of which triangulated from >= 2 cameras
  int64_t off_flight = 0;   // measurements dropped: off the flight on both sides (FlightCheck)
  int64_t not_falling = 0;  // rows taken back: their track did not fall as a ball (fall_check.h)
  int64_t states = 0;       // rows in trajectory.csv
  int64_t roi_hits = 0;     // camera searches that found the ball in their window
  int64_t roi_searches = 0;
  double video_seconds = 0.0;  // time span of the frame sets
  double wall_seconds = 0.0;
  std::vector<std::string> sources_ended_with_error;  // sources that failed mid-run
  // Per source, in the sources' order: damaged input skipped (the frames around it were
  // tracked) and, for live sources, returns after being lost.
  struct Source {
    std::string name;
    int64_t frames_lost = 0, gaps = 0, returns = 0;
  };
  std::vector<Source> sources;
  int64_t rows_found = 0;  // resume: rows (and events) already in the files, found again
  bool stopped = false;    // ended by RunExtras::stop
  int loops = 0;           // times the files started again
  int64_t bounces = 0, hits = 0, points = 0;
  // --realtime only: how far processing fell behind the video's own clock.
  double worst_lag_ms = 0.0;
  int64_t late = 0;   // frame sets finished more than 3 frame periods behind
  std::string score;  // e.g. "games 1-0, points 3-5"

  double measurements_per_second() const {
    return wall_seconds > 0 ? measured / wall_seconds : 0.0;
  }
  std::string Report() const;
};

// Checks sources against the rig (count, image sizes) and runs. `progress` (may be empty) is
// called about twice a second with the frame sets done. Throws p4::Error with the source or
// field at fault.
TrackRunSummary RunTracking(const Rig& rig, const segment::ColorClassSet& classes,
                            const std::vector<std::string>& sources, const std::string& out_dir,
                            const track::FrameSetOptions& options, const GameOptions& game,
                            const std::function<void(int64_t)>& progress,
                            const RunExtras& extras = {});

}  // namespace p4
