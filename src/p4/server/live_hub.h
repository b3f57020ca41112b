// The live view's shared state (paper Figure 6): the tracking loop hands it each frame set
// (LiveSink) and returns at once; an encoder thread turns the cameras' latest pictures into JPEG
// at a reduced rate; the web server's threads read the latest JPEG and state. Frames are dropped,
// never queued: a slow viewer or many viewers cannot slow the tracker down.
//
// State JSON (GET /api/live/state): t, ball {x, y, z, speed, measured} or null, trail (the last
// positions), cameras [{roi [x0, y0, x1, y1] or null, fell_back, detections [{u, v, d,
// accepted}], epipolar [[[u, v], ...], ...]}] in each camera's pixels, score, events (the last
// ones, each with n: its number in the run, from 1, so a client can tell whether it missed one).
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "p4/calib/marker_pose.h"
#include "p4/core/image.h"
#include "p4/geometry/rig.h"
#include "p4/pipeline/live_sink.h"

namespace p4::server {

struct LiveOptions {
  // Calibration markers to show (paper Figure 10: the marker each camera was calibrated with):
  // each camera's pictures are searched for them and the layout's corners are projected through
  // the rig, so the view shows how well the calibration fits. Empty: no markers.
  std::optional<calib::MarkerLayout> markers;
  double state_hz = 30.0;  // state messages a second, at most
  double frame_hz = 10.0;  // pictures a second per camera, at most
  int jpeg_width = 640;    // pictures are scaled to this width
  int jpeg_quality = 70;
  int trail = 60;   // positions in the trail
  int events = 12;  // recent events in the state

  bool IsValid(std::string* error) const;
};

class LiveHub : public LiveSink {
 public:
  LiveHub(const Rig& rig, const std::array<std::string, 2>& players, const LiveOptions& options);
  ~LiveHub() override;
  LiveHub(const LiveHub&) = delete;
  LiveHub& operator=(const LiveHub&) = delete;

  void OnFrameSet(const FrameSet& set, const track::FrameSetResult& result,
                  std::span<const game::Event> events, const game::MatchScore* score) override;
  // A lost camera is marked in the state ("lost": true) until it is back.
  void OnSourceEvent(const SourceEvent& event) override;

  // For the web server (any thread). Null until there is one.
  std::shared_ptr<const std::string> State() const;
  std::shared_ptr<const std::string> Jpeg(int camera) const;
  // The rig's cameras (names, sizes), the players, the table and the markers' projected corners,
  // as JSON.
  const std::string& Config() const { return config_; }
  // The markers found in each camera's latest searched picture (full resolution), as JSON:
  // [[{id, corners: [[u, v] x 4]}, ...] per camera]. "[]" without markers.
  std::shared_ptr<const std::string> Markers() const;
  int64_t frames_offered() const;  // pictures handed to the encoder (for tests)
  int64_t frames_dropped() const;  // pictures the encoder was too busy for

 private:
  void EncodeLoop();

  Rig rig_;
  std::array<std::string, 2> players_;
  LiveOptions options_;
  std::string config_;

  // Tracking thread only.
  std::deque<std::array<double, 3>> trail_;
  std::deque<nlohmann::json> recent_events_;  // as they go into the state
  int64_t events_seen_ = 0;
  std::vector<bool> lost_;  // per camera: a live source being opened again
  TimeNs last_state_t_ = -(int64_t{1} << 62), last_frame_t_ = -(int64_t{1} << 62);

  // The state alone (pointer copies by the tracking and web threads): the encoder, which takes
  // mutex_ for its pictures and may be descheduled holding it (it runs niced), never makes the
  // tracking thread drop a state.
  mutable std::mutex state_mutex_;
  std::shared_ptr<const std::string> state_;
  mutable std::mutex mutex_;  // the pictures, JPEGs and markers below
  std::vector<std::shared_ptr<const std::string>> jpeg_;
  // Handed to the encoder: one picture per camera, I420, copied.
  std::vector<I420Image> pending_;
  std::vector<std::vector<uint8_t>> pending_luma_;  // full-resolution Y, with markers only
  std::shared_ptr<const std::string> markers_json_;
  std::vector<bool> has_pending_;
  bool encoding_ = false, stop_ = false;
  std::atomic<int64_t> offered_{0}, dropped_{0};
  std::condition_variable wake_;
  std::thread encoder_;
};

}  // namespace p4::server
