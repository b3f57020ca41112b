#include "p4/pipeline/track_run.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "p4/core/error.h"
#include "p4/io/event_files.h"
#include "p4/io/run_files.h"
#include "p4/pipeline/frame_set_reader.h"
#include "p4/track/result_hold.h"

namespace p4 {

bool GameOptions::IsValid(std::string* error) const {
  if (!detector.IsValid(error) || !referee.IsValid(error)) return false;
  for (const auto& name : players) {
    if (name.empty()) {
      *error = "player names must not be empty";
      return false;
    }
  }
  return true;
}

std::string TrackRunSummary::Report() const {
  std::string report = fmt::format(
      "{} frame sets ({:.2f} s of video) in {:.2f} s: {} measurements ({:.1f}% of frame sets, {} "
      "from >= 2 cameras), {:.0f} measurements per second, ROI hit rate {:.1f}%",
      frame_sets, video_seconds, wall_seconds, measured,
      frame_sets ? 100.0 * measured / frame_sets : 0.0, multi_view, measurements_per_second(),
      roi_searches ? 100.0 * roi_hits / roi_searches : 0.0);
  if (off_flight > 0) {
    report += fmt::format("; {} measurement(s) off the ball's flight dropped", off_flight);
  }
  if (not_falling > 0) {
    report += fmt::format("; {} row(s) taken back: what they followed did not fall as a ball",
                          not_falling);
  }
  if (!score.empty()) {
    report += fmt::format("; {} bounces, {} strokes, {} points: {}", bounces, hits, points, score);
  }
  for (const Source& s : sources) {
    if (s.gaps > 0) {
      report += fmt::format("; {}: {} damaged frame(s) skipped in {} stretch(es)", s.name,
                            s.frames_lost, s.gaps);
    }
    if (s.returns > 0)
      report += fmt::format("; {}: back {} time(s) after being lost", s.name, s.returns);
  }
  if (loops > 0) report += fmt::format("; the files played {} times", loops + 1);
  if (stopped) report += "; stopped before the sources ended";
  if (worst_lag_ms > 0.0) {
    report += fmt::format("; real time kept: worst lag {:.1f} ms, {} frame sets late", worst_lag_ms,
                          late);
  }
  return report;
}

TrackRunSummary RunTracking(const Rig& rig, const segment::ColorClassSet& classes,
                            const std::vector<std::string>& sources, const std::string& out_dir,
                            const track::FrameSetOptions& options, const GameOptions& game,
                            const std::function<void(int64_t)>& progress, const RunExtras& extras) {
  if (static_cast<int>(sources.size()) != rig.size()) {
    throw Error(fmt::format("the rig has {} camera(s) but {} source(s) were given", rig.size(),
                            sources.size()));
  }
  std::string why;
  if (!options.IsValid(&why)) throw Error("tracking options: " + why);
  if (!game.IsValid(&why)) throw Error("game options: " + why);
  if (!extras.flight_check.IsValid(&why)) throw Error("tracking options: " + why);
  FrameSetReaderOptions reading;
  reading.loop = extras.loop;
  reading.clocks = RigClocks(rig);
  reading.stop = extras.stop;
  FrameSetReader reader(sources, reading);
  for (int i = 0; i < reader.size(); ++i) {
    const VideoInfo& info = reader.info(i);
    const Camera& camera = rig.cameras[i];
    if (info.width != camera.width || info.height != camera.height) {
      throw Error(fmt::format("{}: the video is {}x{} but rig camera '{}' is {}x{}", sources[i],
                              info.width, info.height, camera.name, camera.width, camera.height));
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir + ": cannot create the folder (" + ec.message() + ")");
  RunWriter writer(out_dir, rig, extras.resume);
  track::FrameSetTracker tracker(rig, classes, options);
  game::EventDetector detector(game.detector);
  game::Referee referee(game.referee);

  TrackRunSummary summary;
  // Detected events go to the file and the referee; the referee's (serve, let, point, game,
  // match) to the file, and every point rewrites score.json.
  std::vector<game::Event> published;  // this frame set's, for the live view
  // The referee's decisions: to the file and the live view, and a point rewrites score.json.
  const auto announce = [&](const std::vector<game::Event>& decided) {
    for (const game::Event& r : decided) writer.WriteEvent(r), published.push_back(r);
    if (!decided.empty()) {
      writer.WriteScore(ScoreToJson(referee.score(), referee.points_played(), game.players));
    }
  };
  const auto publish = [&](const std::vector<game::Event>& events) {
    for (const game::Event& e : events) {
      writer.WriteEvent(e);
      published.push_back(e);
      summary.bounces += e.type == "bounce";
      summary.hits += e.type == "hit";
      announce(referee.OnEvent(e));
    }
  };
  const auto tick = [&](double t, bool seen) { announce(referee.OnTime(t, seen)); };
  if (game.enabled) writer.WriteScore(ScoreToJson(referee.score(), 0, game.players));
  // A time-stamp's result, final: to the files and the game.
  // (A one-camera rig's smoother may add measured rows: the counts are of what is written.)
  const auto record = [&](const track::FrameSetResult& r) {
    writer.Write(r);
    if (r.measurement) {
      ++summary.measured;
      if (r.measurement->cameras >= 2) ++summary.multi_view;
    }
    if (r.state) ++summary.states;
    if (game.enabled) {
      const double t = ToSeconds(r.t);
      if (r.measurement) publish(detector.Push(t, r.measurement->position));
      tick(t, r.measurement.has_value());
    }
  };
  std::optional<track::MonocularSmoother> smoother;
  if (rig.size() == 1 && extras.smooth_one_camera) {
    track::MonocularSmootherOptions smoothing;
    smoothing.pixel_sigma = options.pixel_sigma;
    smoothing.diameter_sigma = options.diameter_sigma;
    smoothing.fit.model = track::FlightModelOf(options.tracker);
    smoother.emplace(rig.cameras[0], smoothing);
  }
  // New tracks are confirmed by the ball's flight: the rows wait for the revisions that brings.
  std::optional<track::ResultHold> hold;
  if (options.confirm_tracks) hold.emplace(track::RowHoldSeconds(options));
  std::optional<track::FlightCheck> flight_check;
  if (rig.size() >= 2 && extras.check_flight) {
    track::FlightCheckOptions checking = extras.flight_check;
    checking.model = track::FlightModelOf(options.tracker);
    flight_check.emplace(checking);
  }
  // Confirmed first (the hold), then checked against the flight (2+ cameras) or smoothed (one).
  const auto smooth = [&](track::FrameSetResult r) {
    if (flight_check) {
      for (auto& c : flight_check->Push(std::move(r))) record(c);
      return;
    }
    if (!smoother) return record(r);
    for (const auto& s : smoother->Push(std::move(r))) record(s);
  };
  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  FrameSet set;
  std::optional<TimeNs> first_t;
  auto paced_from = start;
  TimeNs last_t = 0;
  for (const std::string& name : sources) summary.sources.push_back({name});
  const auto take_source_news = [&] {
    for (const SourceGap& g : reader.TakeGaps()) {
      summary.sources[g.source].frames_lost += g.gap.frames_lost;
      ++summary.sources[g.source].gaps;
      if (extras.on_gap) extras.on_gap(sources[g.source], g.gap);
    }
    for (const SourceEvent& e : reader.TakeSourceEvents()) {
      summary.sources[e.source].returns += e.back ? 1 : 0;
      if (extras.on_source) extras.on_source(sources[e.source], e);
      if (extras.live) extras.live->OnSourceEvent(e);
    }
  };
  while (reader.Next(&set)) {
    take_source_news();
    if (extras.stop && extras.stop->load()) {
      summary.stopped = true;
      break;
    }
    if (!first_t) {
      first_t = set.t;
      paced_from = std::chrono::steady_clock::now();  // the clock starts with the first picture
    }
    if (set.t <= last_t && summary.frame_sets > 0) continue;  // time must increase
    const TimeNs last_t_before = last_t;
    last_t = set.t;
    if (extras.realtime) {
      // Recorded video at its own pace: frame set t is processed at start + (t - first t).
      std::this_thread::sleep_until(paced_from + std::chrono::nanoseconds(set.t - *first_t));
    }
    const track::FrameSetResult result = tracker.Process(set.t, set.images, set.times);
    published.clear();
    if (hold) {
      for (auto& r : hold->Push(result)) smooth(std::move(r));
    } else {
      smooth(result);
    }
    if (extras.live) {
      extras.live->OnFrameSet(set, result, published, game.enabled ? &referee.score() : nullptr);
    }
    if (extras.realtime) {
      const auto due = paced_from + std::chrono::nanoseconds(set.t - *first_t);
      const double lag_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - due).count();
      summary.worst_lag_ms = std::max(summary.worst_lag_ms, lag_ms);
      // A live camera queues a few frames (V4L2 and network sources hold 3-4): a frame set
      // finished within 3 frame periods of its time lost nothing.
      if (summary.frame_sets > 0 && lag_ms > 3e3 * ToSeconds(set.t - last_t_before)) ++summary.late;
    }
    ++summary.frame_sets;
    for (const auto& s : result.searches) {
      if (s.roi.empty()) continue;
      ++summary.roi_searches;
      if (!s.fell_back) ++summary.roi_hits;
    }
    const auto now = std::chrono::steady_clock::now();
    if (progress && now - last_progress > std::chrono::milliseconds(500)) {
      last_progress = now;
      progress(summary.frame_sets);
    }
  }
  take_source_news();
  // Stopped while waiting for a source to come back: Next() returned at the stop.
  if (extras.stop && extras.stop->load()) summary.stopped = true;
  if (hold) {
    for (auto& r : hold->Flush(tracker.Finish())) smooth(std::move(r));
  }
  summary.not_falling = tracker.taken_back();
  if (smoother) {
    for (const auto& r : smoother->Flush()) record(r);
  }
  if (flight_check) {
    for (const auto& r : flight_check->Flush()) record(r);
    summary.off_flight = flight_check->dropped();
  }
  if (game.enabled) {
    publish(detector.Flush());
    tick(ToSeconds(last_t), false);
    const auto& score = referee.score();
    summary.points = referee.points_played();
    summary.score = fmt::format("games {}-{}, points {}-{}", score.games()[0], score.games()[1],
                                score.points()[0], score.points()[1]);
    writer.WriteScore(ScoreToJson(score, referee.points_played(), game.players));
  }
  summary.sources_ended_with_error = reader.ended_with_error();
  summary.rows_found = writer.rows_found();
  summary.loops = reader.loops();
  summary.video_seconds = first_t ? ToSeconds(last_t - *first_t) : 0.0;
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace p4
