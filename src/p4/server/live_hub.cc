#include "p4/server/live_hub.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "p4/core/table.h"
#include "p4/io/event_files.h"
#include "p4/server/web_server.h"

namespace p4::server {

bool LiveOptions::IsValid(std::string* error) const {
  if (!(state_hz > 0.0) || !(frame_hz > 0.0) || jpeg_width < 64 || jpeg_quality < 10 ||
      jpeg_quality > 100 || trail < 0 || events < 0) {
    *error = "live view: rates must be positive, jpeg_width >= 64, jpeg_quality 10-100";
    return false;
  }
  return true;
}

LiveHub::LiveHub(const Rig& rig, const std::array<std::string, 2>& players,
                 const LiveOptions& options)
    : rig_(rig), players_(players), options_(options), lost_(rig.cameras.size(), false) {
  nlohmann::ordered_json config;
  config["players"] = players;
  config["table"] = {{"length", table::kLength},        {"width", table::kWidth},
                     {"net_height", table::kNetHeight}, {"net_half_length", table::kNetHalfLength},
                     {"floor_z", table::kFloorZ},       {"ball_radius", table::kBallRadius}};
  for (const Camera& c : rig.cameras) {
    const Eigen::Vector3d centre = c.Center();
    config["cameras"].push_back({{"name", c.name},
                                 {"width", c.width},
                                 {"height", c.height},
                                 {"centre", {centre.x(), centre.y(), centre.z()}}});
  }
  config["markers"] = nlohmann::json::array();
  if (options.markers) {
    for (const Camera& c : rig.cameras) {
      nlohmann::ordered_json projected = nlohmann::ordered_json::array();
      for (const auto& [id, corners] : options.markers->corners) {
        nlohmann::ordered_json quad = nlohmann::ordered_json::array();
        for (const auto& w : corners) {
          if (const auto p = c.Project(w)) quad.push_back({p->x(), p->y()});
        }
        if (quad.size() == 4) projected.push_back({{"id", id}, {"corners", quad}});
      }
      config["markers"].push_back(projected);
    }
  }
  config_ = config.dump();
  markers_json_ = std::make_shared<const std::string>("[]");
  jpeg_.resize(rig.size());
  pending_.resize(rig.size());
  pending_luma_.resize(rig.size());
  has_pending_.assign(rig.size(), false);
  encoder_ = std::thread([this] { EncodeLoop(); });
}

LiveHub::~LiveHub() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  encoder_.join();
}

std::shared_ptr<const std::string> LiveHub::State() const {
  std::lock_guard lock(state_mutex_);
  return state_;
}

std::shared_ptr<const std::string> LiveHub::Jpeg(int camera) const {
  std::lock_guard lock(mutex_);
  if (camera < 0 || camera >= static_cast<int>(jpeg_.size())) return nullptr;
  return jpeg_[camera];
}

std::shared_ptr<const std::string> LiveHub::Markers() const {
  std::lock_guard lock(mutex_);
  return markers_json_;
}

int64_t LiveHub::frames_offered() const { return offered_; }

int64_t LiveHub::frames_dropped() const { return dropped_; }

void LiveHub::OnSourceEvent(const SourceEvent& event) {
  if (event.source < 0 || event.source >= rig_.size()) return;
  lost_[event.source] = !event.back;
  last_state_t_ = -(int64_t{1} << 62);  // the next frame set's state says it at once...
  // ...and the state published now says it too (with every camera lost there is no next set).
  // (A rare event: the lock is held for pointer copies only, as the web threads hold it.)
  const std::shared_ptr<const std::string> published = State();
  if (!published) return;
  nlohmann::json state = nlohmann::json::parse(*published);
  if (event.source < static_cast<int>(state["cameras"].size())) {
    state["cameras"][event.source]["lost"] = !event.back;
  }
  auto text = std::make_shared<const std::string>(state.dump());
  std::lock_guard lock(state_mutex_);
  state_ = std::move(text);
}

void LiveHub::OnFrameSet(const FrameSet& set, const track::FrameSetResult& result,
                         std::span<const game::Event> events, const game::MatchScore* score) {
  if (result.state) {
    trail_.push_back(
        {result.state->position.x(), result.state->position.y(), result.state->position.z()});
    while (static_cast<int>(trail_.size()) > options_.trail) trail_.pop_front();
  }
  for (const game::Event& e : events) {
    recent_events_.push_back(nlohmann::json::parse(EventToJsonLine(e)));  // once per event
    recent_events_.back()["n"] = ++events_seen_;
    while (static_cast<int>(recent_events_.size()) > options_.events) recent_events_.pop_front();
  }
  // Pictures: at most frame_hz, and only when the encoder is free (else this one is dropped).
  if (set.t - last_frame_t_ >= static_cast<TimeNs>(1e9 / options_.frame_hz)) {
    last_frame_t_ = set.t;  // this slot is used or dropped, not retried
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (lock.owns_lock() && !encoding_) {
      for (int c = 0; c < rig_.size() && c < static_cast<int>(set.images.size()); ++c) {
        if (!set.images[c]) continue;
        const int factor =
            std::max(1, (set.images[c]->width + options_.jpeg_width - 1) / options_.jpeg_width);
        DownsampleToI420(*set.images[c], factor, &pending_[c]);
        if (options_.markers) {  // markers are small: they are searched at full resolution
          const ImageView& view = *set.images[c];
          auto& luma = pending_luma_[c];
          luma.resize(static_cast<std::size_t>(view.width) * view.height);
          for (int y = 0; y < view.height; ++y) {
            const uint8_t* row = view.planes[0].Row(y);
            uint8_t* out = luma.data() + static_cast<std::size_t>(y) * view.width;
            if (view.format == PixelFormat::kYUYV) {
              for (int x = 0; x < view.width; ++x) out[x] = row[2 * x];
            } else {
              std::copy(row, row + view.width, out);
            }
          }
        }
        has_pending_[c] = true;
        ++offered_;
      }
      lock.unlock();
      wake_.notify_one();
    } else {
      ++dropped_;
    }
  }
  if (set.t - last_state_t_ < static_cast<TimeNs>(1e9 / options_.state_hz) && events.empty()) {
    return;
  }
  const TimeNs skipped_state_t = last_state_t_;
  last_state_t_ = set.t;
  nlohmann::json state;
  state["t"] = ToSeconds(set.t);
  if (result.state) {
    const auto& s = *result.state;
    state["ball"] = {{"x", s.position.x()},
                     {"y", s.position.y()},
                     {"z", s.position.z()},
                     {"speed", s.velocity.norm()},
                     {"measured", s.measured}};
  } else {
    state["ball"] = nullptr;
  }
  state["trail"] = nlohmann::json::array();
  for (const auto& p : trail_) state["trail"].push_back(p);
  // Per camera: its search window, its candidates, and the epipolar lines of the ball as the
  // other cameras saw it (paper Figure 6: red ROI, yellow lines).
  std::vector<std::vector<const track::Detection*>> accepted(rig_.size());
  for (const auto& d : result.detections) {
    if (d.accepted) accepted[d.camera].push_back(&d);
  }
  for (int c = 0; c < rig_.size(); ++c) {
    nlohmann::json cam;
    const auto& search =
        c < static_cast<int>(result.searches.size()) ? result.searches[c] : track::CameraSearch{};
    cam["present"] = search.present;
    cam["lost"] = static_cast<bool>(lost_[c]);
    if (!search.roi.empty()) {
      cam["roi"] = {search.roi.x0, search.roi.y0, search.roi.x1, search.roi.y1};
    } else {
      cam["roi"] = nullptr;
    }
    cam["fell_back"] = search.fell_back;
    cam["detections"] = nlohmann::json::array();
    for (const auto& d : result.detections) {
      if (d.camera != c) continue;
      cam["detections"].push_back({{"u", std::round(d.observed.x() * 10) / 10},
                                   {"v", std::round(d.observed.y() * 10) / 10},
                                   {"d", std::round(d.diameter_px * 10) / 10},
                                   {"accepted", d.accepted}});
    }
    cam["epipolar"] = nlohmann::json::array();
    for (int o = 0; o < rig_.size(); ++o) {
      if (o == c) continue;
      for (const track::Detection* d : accepted[o]) {
        nlohmann::json line = nlohmann::json::array();
        // The ray of the other camera's ball, 0.3-30 m deep, even in inverse depth; points a
        // little beyond the picture are kept so the drawn line reaches its edges.
        const Camera& from = rig_.cameras[o];
        const Camera& to = rig_.cameras[c];
        const Eigen::Vector3d origin = from.Center(), ray = from.RayDirection(d->pixel);
        for (int k = 0; k < 40; ++k) {
          const double s = k / 39.0;
          const auto p = to.Project(origin + ray / ((1.0 - s) / 0.3 + s / 30.0));
          if (!p || p->x() < -to.width || p->x() > 2 * to.width || p->y() < -to.height ||
              p->y() > 2 * to.height) {
            continue;
          }
          line.push_back({std::round(p->x() * 10) / 10, std::round(p->y() * 10) / 10});
        }
        cam["epipolar"].push_back(line);
      }
    }
    state["cameras"].push_back(cam);
  }
  if (score) {
    state["score"] = ScoreToJson(*score, 0, players_);
  } else {
    state["score"] = nullptr;
  }
  state["events"] = recent_events_;
  auto text = std::make_shared<const std::string>(state.dump());
  // Never wait for a reader: the UI's threads run at the lowest priority and one holding the lock
  // may not get the CPU for a while. Busy: this state is dropped, the next frame set publishes.
  std::unique_lock lock(state_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) {
    last_state_t_ = skipped_state_t;
    return;
  }
  state_ = std::move(text);
}

void LiveHub::EncodeLoop() {
  YieldToTracking();
  // OpenCV's resize, colour conversion and JPEG encoder would run on its own worker threads, at
  // normal priority: they took the tracking's CPU (60 s of 3 x 720p @ 60 fps with the live view:
  // 23 frame sets late, worst lag 121 ms). One thread, this one, niced. (Process-wide: nothing
  // else of a tracking run uses OpenCV's parallel loops.)
  cv::setNumThreads(1);
  std::vector<I420Image> work(rig_.size());
  std::vector<std::vector<uint8_t>> luma(rig_.size());
  std::vector<bool> todo(rig_.size());
  nlohmann::json markers = nlohmann::json::array();
  for (int c = 0; c < rig_.size(); ++c) markers.push_back(nlohmann::json::array());
  std::vector<uint8_t> buffer;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] {
        return stop_ ||
               std::find(has_pending_.begin(), has_pending_.end(), true) != has_pending_.end();
      });
      if (stop_) return;
      for (int c = 0; c < rig_.size(); ++c) {
        todo[c] = has_pending_[c];
        if (todo[c]) std::swap(work[c], pending_[c]);
        if (todo[c] && options_.markers) std::swap(luma[c], pending_luma_[c]);
        has_pending_[c] = false;
      }
      encoding_ = true;
    }
    for (int c = 0; c < rig_.size(); ++c) {
      if (!todo[c]) continue;
      const I420Image& f = work[c];
      const cv::Mat yuv(f.height() * 3 / 2, f.width(), CV_8UC1, const_cast<uint8_t*>(f.y()));
      cv::Mat bgr;
      cv::cvtColor(yuv, bgr, cv::COLOR_YUV2BGR_I420);
      cv::imencode(".jpg", bgr, buffer, {cv::IMWRITE_JPEG_QUALITY, options_.jpeg_quality});
      auto jpeg = std::make_shared<const std::string>(buffer.begin(), buffer.end());
      {
        std::lock_guard lock(mutex_);
        jpeg_[c] = std::move(jpeg);
      }
      const Camera& camera = rig_.cameras[c];
      if (options_.markers &&
          luma[c].size() == static_cast<std::size_t>(camera.width) * camera.height) {
        const cv::Mat gray(camera.height, camera.width, CV_8UC1, luma[c].data());
        markers[c] = nlohmann::json::array();
        for (const auto& m : calib::DetectMarkers(gray, options_.markers->dictionary)) {
          nlohmann::json quad = nlohmann::json::array();
          for (const auto& p : m.corners) quad.push_back({p.x(), p.y()});
          markers[c].push_back({{"id", m.id}, {"corners", quad}});
        }
        auto text = std::make_shared<const std::string>(markers.dump());
        std::lock_guard lock(mutex_);
        markers_json_ = std::move(text);
      }
    }
    std::lock_guard lock(mutex_);
    encoding_ = false;
  }
}

}  // namespace p4::server
