#include "p4/game/event_detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "p4/io/flight_file.h"
#include "p4/sim/match.h"

namespace p4::game {
namespace {

// Runs the detector over a trajectory sampled at `fps` with Gaussian noise (sigma_m per axis).
std::vector<Event> Detect(const sim::Trajectory& trajectory, double t0, double t1, double fps,
                          double sigma_m, uint32_t seed = 3) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_m);
  EventDetector detector;
  std::vector<Event> events;
  for (double t = t0; t <= t1; t += 1.0 / fps) {
    const auto s = trajectory.At(t);
    if (!s) continue;
    const Eigen::Vector3d p = s->position + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    for (auto& e : detector.Push(t, p)) events.push_back(e);
  }
  for (auto& e : detector.Flush()) events.push_back(e);
  return events;
}

std::vector<Event> OfType(const std::vector<Event>& events, const std::string& type) {
  std::vector<Event> out;
  std::copy_if(events.begin(), events.end(), std::back_inserter(out),
               [&](const Event& e) { return e.type == type; });
  return out;
}

// For each truth event, the detected event of the same type nearest in time within `within_s`.
struct Matched {
  int found = 0, missed = 0, extra = 0;
  std::vector<double> position_mm, time_ms;
};
Matched Match(const std::vector<Event>& truth, const std::vector<Event>& detected,
              double within_s) {
  Matched m;
  std::vector<bool> used(detected.size(), false);
  for (const Event& t : truth) {
    int best = -1;
    for (std::size_t i = 0; i < detected.size(); ++i) {
      if (used[i] || std::abs(detected[i].t - t.t) > within_s) continue;
      if (best < 0 || std::abs(detected[i].t - t.t) < std::abs(detected[best].t - t.t)) best = i;
    }
    if (best < 0) {
      ++m.missed;
      continue;
    }
    used[best] = true;
    ++m.found;
    m.time_ms.push_back(1000.0 * std::abs(detected[best].t - t.t));
    if (t.position && detected[best].position) {
      m.position_mm.push_back(1000.0 *
                              (t.position->head<2>() - detected[best].position->head<2>()).norm());
    }
  }
  m.extra = static_cast<int>(std::count(used.begin(), used.end(), false));
  return m;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Simulated play, sampled as a 120 fps tracker would see it (3 mm of noise): every bounce is
// found once, on the right side, within millimetres and a millisecond or two.
TEST(EventDetector, FindsEverySimulatedBounceAndHit) {
  sim::MatchOptions options;
  options.points = 12;
  options.seed = 8;
  const sim::MatchResult match = sim::SimulateMatch(options);
  const auto events = Detect(match.trajectory, 0.0, match.duration, 120.0, 0.003);
  const auto truth = match.events;
  const Matched bounces = Match(OfType(truth, "bounce"), OfType(events, "bounce"), 0.02);
  std::printf("bounces: %d found, %d missed, %d extra; median %.2f mm, %.2f ms\n", bounces.found,
              bounces.missed, bounces.extra, Median(bounces.position_mm), Median(bounces.time_ms));
  EXPECT_GE(bounces.found, 30);
  EXPECT_EQ(bounces.missed, 0);
  EXPECT_EQ(bounces.extra, 0);
  EXPECT_LT(Median(bounces.position_mm), 5.0);
  EXPECT_LT(Median(bounces.time_ms), 2.0);
  for (const Event& e : OfType(events, "bounce")) {
    EXPECT_EQ(e.side, table::SideOf(e.position->x()));
  }
  // Hits: the serve's strike and every return (truth "serve" and "hit").
  std::vector<Event> strikes;
  for (const Event& e : truth) {
    if (e.type == "serve" || e.type == "hit") strikes.push_back(e);
  }
  const Matched hits = Match(strikes, OfType(events, "hit"), 0.03);
  std::printf("hits: %d found, %d missed, %d extra\n", hits.found, hits.missed, hits.extra);
  EXPECT_GE(hits.found, static_cast<int>(0.95 * strikes.size()));
  EXPECT_LE(hits.extra, 2);
  for (const char* type : {"out", "net", "floor"}) {
    const Matched m = Match(OfType(truth, type), OfType(events, type), 0.02);
    std::printf("%s: %d found, %d missed\n", type, m.found, m.missed);
    EXPECT_EQ(m.missed, 0) << type;
  }
}

// The real flights: each flight's table bounces (the local minima of z below 4 cm over the
// table) and nothing else that is a bounce.
TEST(EventDetector, FindsExactlyTheBouncesOfTheRealFlights) {
  const std::string dir = std::string(P4_SHARED_DATA) + "/trajectories/tt3d";
  int flights = 0, truth_bounces = 0, found = 0, extra = 0;
  std::vector<double> time_ms;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const RealFlight flight = ReadTt3dFlight(entry.path().string(), 0.0);
    EventDetector detector;
    std::vector<Event> events;
    for (const auto& s : flight.trajectory.samples()) {
      for (auto& e : detector.Push(s.t, s.state.position)) events.push_back(e);
    }
    for (auto& e : detector.Flush()) events.push_back(e);
    const Matched m = Match(flight.bounces, OfType(events, "bounce"), 0.02);
    ++flights;
    truth_bounces += static_cast<int>(flight.bounces.size());
    found += m.found;
    extra += m.extra;
    time_ms.insert(time_ms.end(), m.time_ms.begin(), m.time_ms.end());
    EXPECT_EQ(m.missed, 0) << entry.path();
    EXPECT_EQ(m.extra, 0) << entry.path();
  }
  std::printf("%d flights: %d of %d bounces found, %d extra, median time offset %.2f ms\n", flights,
              found, truth_bounces, extra, Median(time_ms));
  EXPECT_EQ(flights, 139);
}

// Named cases: a ball into the net, a ball that flies past the table's end (out), a drop on
// the floor.
sim::Trajectory Ballistic(const Eigen::Vector3d& p, const Eigen::Vector3d& v, double t1) {
  sim::Trajectory trajectory;
  for (double t = 0.0; t <= t1; t += 0.001) {
    sim::BallState s;
    s.position = p + t * v + 0.5 * t * t * Eigen::Vector3d(0, 0, -9.81);
    s.velocity = v + t * Eigen::Vector3d(0, 0, -9.81);
    trajectory.Append(t, s);
  }
  trajectory.EndSegment();
  return trajectory;
}

TEST(EventDetector, ABallThroughTheNetPlaneBelowItsTopTouchedTheNet) {
  // From A's end, low and flat: it reaches x = 0 at about 8 cm height.
  const auto trajectory = Ballistic({-1.2, 0.1, 0.20}, {6.0, 0.0, 0.5}, 0.3);
  const auto events = Detect(trajectory, 0.0, 0.3, 120.0, 0.0);
  const auto net = OfType(events, "net");
  ASSERT_EQ(net.size(), 1u);
  EXPECT_NEAR(net[0].t, 0.2, 0.01);
}

TEST(EventDetector, PastTheEndWithoutTouchingIsOut) {
  const auto trajectory = Ballistic({0.5, 0.0, 0.30}, {8.0, 0.0, 0.0}, 0.35);
  const auto events = Detect(trajectory, 0.0, 0.35, 120.0, 0.0);
  const auto out = OfType(events, "out");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_GT(out[0].position->x(), table::kHalfLength);
  EXPECT_TRUE(OfType(events, "bounce").empty());
}

TEST(EventDetector, NothingFromAStraightFlightOrTooFewPoints) {
  const auto trajectory = Ballistic({-1.0, 0.0, 0.30}, {3.0, 0.2, 2.0}, 0.3);
  EXPECT_TRUE(Detect(trajectory, 0.0, 0.3, 120.0, 0.002).empty());
  EventDetector detector;
  EXPECT_TRUE(detector.Push(0.0, {0, 0, 0.3}).empty());
  EXPECT_TRUE(detector.Flush().empty());
}

}  // namespace
}  // namespace p4::game
