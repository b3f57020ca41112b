// A world for the sync tests: a rally of ball flights over the table, seen by two cameras whose
// clocks differ, with detection noise, false candidates and dropped frames.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "p4/geometry/camera.h"
#include "p4/geometry/test_cameras.h"
#include "p4/sync/track_2d.h"

namespace p4::sync::testing {

// Flights from end to end, each of its own length, height and aim, for `seconds`.
class Rally {
 public:
  Rally(double seconds, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double t = 0.3;
    int direction = 1;
    while (t < seconds) {
      Flight f;
      f.t0 = t;
      f.duration = 0.45 + 0.4 * u(rng);
      f.from = {-1.6 * direction, -0.6 + 1.2 * u(rng), 0.15 + 0.3 * u(rng)};
      f.to = {1.6 * direction, -0.6 + 1.2 * u(rng), 0.1 + 0.3 * u(rng)};
      flights_.push_back(f);
      t += f.duration + 0.02;
      direction = -direction;
    }
  }
  // Which flight the ball is in at world time t (-1 between flights).
  int FlightAt(double t) const {
    for (int i = 0; i < static_cast<int>(flights_.size()); ++i) {
      const Flight& f = flights_[static_cast<std::size_t>(i)];
      if (t >= f.t0 && t <= f.t0 + f.duration) return i;
    }
    return -1;
  }
  // Where the ball is at world time t (nullopt between flights).
  std::optional<Eigen::Vector3d> At(double t) const {
    const int i = FlightAt(t);
    if (i < 0) return std::nullopt;
    const Flight& f = flights_[static_cast<std::size_t>(i)];
    const double s = t - f.t0, d = f.duration;
    Eigen::Vector3d p = f.from + (f.to - f.from) * (s / d);
    p.z() += 0.5 * 9.81 * s * (d - s);  // a parabola through both ends
    return p;
  }

 private:
  struct Flight {
    double t0 = 0.0, duration = 0.0;
    Eigen::Vector3d from, to;
  };
  std::vector<Flight> flights_;
};

struct Recording {
  double fps = 60.0;
  double offset_s = 0.0;  // world time of stamp 0
  double drift_ppm = 0.0;
  double seconds = 12.0;
  double noise_px = 0.3;
  double drop_rate = 0.0;
  double dark_from_s = -1.0, dark_to_s = -1.0;  // stamps without frames (a camera that drops out)
  int false_candidates = 1;                     // per frame, anywhere
  bool lamp = true;                             // a static candidate every frame
  double line_time_s = 0.0;                     // rolling shutter: each row this much later
  // Each flight's views lean by their own constant 2D offset (its sigma per axis, px): the lit
  // half, the background behind it, the encoder's chroma, alike along one flight.
  double lean_px = 0.0;
};

// The camera's frames (stamps in its own clock) with the ball's pixel among the candidates.
inline std::vector<FrameCandidates> Record(const Camera& camera, const Rally& rally,
                                           const Recording& r, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, r.noise_px);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<FrameCandidates> frames;
  const double rate = 1.0 + 1e-6 * r.drift_ppm;
  for (int k = 0; k / r.fps < r.seconds; ++k) {
    const double stamp = k / r.fps;
    if (u(rng) < r.drop_rate || (stamp >= r.dark_from_s && stamp < r.dark_to_s)) continue;
    FrameCandidates frame{stamp, {}};
    // The ball where it was when its row was read (the row found by a few rounds).
    std::optional<Eigen::Vector2d> seen;
    double row = 0.0;
    for (int round = 0; round < (r.line_time_s > 0.0 ? 4 : 1); ++round) {
      seen.reset();
      if (const auto p = rally.At(r.offset_s + rate * (stamp + r.line_time_s * row))) {
        if (const auto px = camera.Project(*p); px && camera.InImage(*px)) seen = *px;
      }
      if (!seen) break;
      row = seen->y();
    }
    if (seen) {
      Eigen::Vector2d lean = Eigen::Vector2d::Zero();
      if (r.lean_px > 0.0) {
        // Drawn from the flight's index, so that every frame of a flight leans alike.
        std::mt19937_64 flight_rng(
            seed * 7919 + static_cast<uint64_t>(rally.FlightAt(r.offset_s + rate * stamp) + 1));
        std::normal_distribution<double> lean_noise(0.0, r.lean_px);
        lean = {lean_noise(flight_rng), lean_noise(flight_rng)};
      }
      frame.pixels.push_back(*seen + lean + Eigen::Vector2d(noise(rng), noise(rng)));
    }
    if (r.lamp) frame.pixels.push_back({100.0 + noise(rng), 80.0 + noise(rng)});
    for (int i = 0; i < r.false_candidates; ++i) {
      frame.pixels.push_back({u(rng) * camera.width, u(rng) * camera.height});
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

inline Camera SideCamera() { return p4::testing::MakeCamera("side", {0.2, -3.5, 1.5}); }
inline Camera EndCamera() {
  return p4::testing::MakeCamera("end", {-4.0, -0.8, 2.0}, {0.3, 0.0, 0.0},
                                 {-0.12, 0.05, 0.001, -0.0005, 0.0});
}

}  // namespace p4::sync::testing
