// The track initiator and the result hold: what flies becomes a track, what stays or flickers
// does not, and the rows before the confirmation are revised before they are written.
#include "p4/track/track_initiator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "p4/track/result_hold.h"

namespace p4::track {
namespace {

constexpr double kRate = 120.0;

// A 3D candidate at t_s seconds, measured with `sigma` (m) on each axis.
TrackletPoint PointAt(double t_s, const Eigen::Vector3d& p, double sigma, int detection) {
  TrackletPoint out;
  out.t = FromSeconds(t_s);
  out.measurement.position = p;
  out.measurement.covariance = sigma * sigma * Eigen::Matrix3d::Identity();
  out.measurement.cameras = 2;
  out.detections = {detection};
  return out;
}

// The k-th set at 120 per second, 2 mm of noise.
TrackletPoint Point(int k, const Eigen::Vector3d& p, int detection) {
  return PointAt(k / kRate, p, 0.002, detection);
}

// A drive at 8 m/s, rising and falling, measured with 2 mm of noise.
Eigen::Vector3d Flight(int k, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.002);
  const double t = k / kRate;
  return Eigen::Vector3d(-1.2 + 8.0 * t + noise(*rng), 0.1 + noise(*rng),
                         0.2 + 1.5 * t - 4.9 * t * t + noise(*rng));
}

TEST(TrackInitiator, TheFlyingBallIsConfirmedAmongALampAndAFlicker) {
  std::mt19937 rng(3);
  TrackInitiator initiator;
  const Eigen::Vector3d lamp(2.0, -0.5, 0.05);
  std::optional<Tracklet> confirmed;
  int confirmed_at = -1;
  for (int k = 0; k < 40 && !confirmed; ++k) {
    std::vector<TrackletPoint> candidates = {Point(k, lamp, 0)};
    if (k >= 10) candidates.push_back(Point(k, Flight(k - 10, &rng), 1));
    // A speck that comes and goes at random places.
    if (k % 3 == 0) candidates.push_back(Point(k, Eigen::Vector3d(0.3 * (k % 7), 1.0, 0.4), 2));
    confirmed = initiator.Push(FromSeconds(k / kRate), candidates);
    if (confirmed) confirmed_at = k;
  }
  ASSERT_TRUE(confirmed.has_value());
  // 8 m/s at 120 sets per second: 4 points travel 20 cm, so the fourth point confirms.
  EXPECT_EQ(confirmed_at, 13);
  ASSERT_EQ(confirmed->points.size(), 4u);
  for (const auto& p : confirmed->points) EXPECT_EQ(p.detections, std::vector<int>{1});
  EXPECT_EQ(confirmed->flight_start, 0u);  // one flight
}

// The drive above, its points of still and moving views (FrameSetTracker: a still speck's ray)
// from `flagged_from` on (of the first `flagged` of them): those count for nothing toward its
// confirmation by travel. Returns the set it is confirmed at, if any of 20.
std::optional<int> ConfirmedWithStillAndMoving(int flagged_from, int flagged) {
  std::mt19937 rng(3);
  TrackInitiator initiator;
  for (int k = 0; k < 20; ++k) {
    TrackletPoint p = Point(k, Flight(k, &rng), 1);
    p.still_and_moving = k >= flagged_from && k < flagged_from + flagged;
    if (initiator.Push(FromSeconds(k / kRate), std::vector<TrackletPoint>{p})) return k;
  }
  return std::nullopt;
}

TEST(TrackInitiator, PointsOfAStillSpecksRayCountForNothingTowardTravel) {
  EXPECT_EQ(ConfirmedWithStillAndMoving(0, 0), 3);  // 4 points of 8 m/s at 120 per second
  // Every point such: not by its travel; by its fall with gravity once it spans fall_span_s
  // (0.1 s: the 13th point), which a speck's ray paired with a moving thing seldom fits.
  EXPECT_EQ(ConfirmedWithStillAndMoving(0, 20), 12);
  // One such point among them: the fifth confirms (4 that count).
  EXPECT_EQ(ConfirmedWithStillAndMoving(1, 1), 4);
}

TEST(TrackInitiator, ATrackletThroughAHitKnowsWhereItsFlightStarts) {
  // 240 sets a second: 2 m/s for 9 sets (6.7 cm, no confirmation), then hit back at 7 m/s; the
  // gate takes the ball through the hit (4 cm off the drift's prediction).
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.002);
  const auto ball = [&](int k) -> Eigen::Vector3d {
    const double t = k / 240.0, hit = 8 / 240.0;
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    if (t <= hit) return Eigen::Vector3d(2.0 * t, 0.0, 0.3 - 4.9 * t * t) + n;
    const double s = t - hit;
    return Eigen::Vector3d(2.0 * hit - 7.0 * s, -s, 0.3 - 4.9 * hit * hit + s - 4.9 * s * s) + n;
  };
  TrackInitiator initiator;
  std::optional<Tracklet> confirmed;
  int k = 0;
  for (; k < 30 && !confirmed; ++k) {
    confirmed =
        initiator.Push(FromSeconds(k / 240.0), std::vector{PointAt(k / 240.0, ball(k), 0.002, 0)});
  }
  ASSERT_TRUE(confirmed.has_value());
  ASSERT_GT(confirmed->points.size(), 9u) << "the tracklet should span the hit";
  EXPECT_EQ(confirmed->points.front().t, 0);
  // Its flight: from the hit (set 8, the contact's own point fits either flight) on.
  EXPECT_GE(confirmed->flight_start, 8u);
  EXPECT_LE(confirmed->flight_start, 9u);
}

TEST(TrackInitiator, WhatStaysOrFlickersIsNeverConfirmed) {
  TrackInitiator initiator;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.003);
  for (int k = 0; k < 200; ++k) {
    std::vector<TrackletPoint> candidates;
    // A lamp measured with noise, and a shoe seen in one set of three, moving slowly.
    candidates.push_back(
        Point(k, Eigen::Vector3d(1.0 + noise(rng), 0.0 + noise(rng), 0.5 + noise(rng)), 0));
    if (k % 3 == 0) candidates.push_back(Point(k, Eigen::Vector3d(0.01 * k, 1.5, -0.7), 1));
    ASSERT_FALSE(initiator.Push(FromSeconds(k / kRate), candidates).has_value()) << k;
  }
}

// A hand or a shirt of the ball's colour moving at 0.8 m/s, seen in every set, travels 20 cm in
// the initiator's 0.25 s: more than a ball's 10 cm, but too slowly for a ball that does not fall.
TEST(TrackInitiator, ASlowHandThatDoesNotFallIsNeverConfirmed) {
  TrackInitiator initiator;
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (int k = 0; k < 120; ++k) {
    const double t = k / kRate;
    const Eigen::Vector3d hand(1.9 + 0.8 * t + noise(rng), 0.3 + noise(rng),
                               0.25 + 0.03 * std::sin(6.0 * t) + noise(rng));
    ASSERT_FALSE(initiator.Push(FromSeconds(t), {{Point(k, hand, 0)}}).has_value()) << k;
  }
}

// One camera at (0, -3.5, 1.5) places each view by its diameter: 12 cm of noise along the ray
// (a 9 px ball's diameter to 0.35 px at 3.5 m), 2 mm across it.
TrackletPoint OneCameraPoint(int k, const Eigen::Vector3d& p, std::mt19937* rng, int detection) {
  const Eigen::Vector3d camera(0.0, -3.5, 1.5);
  const Eigen::Vector3d ray = (p - camera).normalized();
  std::normal_distribution<double> along(0.0, 0.12), across(0.0, 0.002);
  const Eigen::Matrix3d across_ray = Eigen::Matrix3d::Identity() - ray * ray.transpose();
  const Eigen::Vector3d a(across(*rng), across(*rng), across(*rng));
  TrackletPoint out = Point(k, p + along(*rng) * ray + across_ray * a, detection);
  out.measurement.covariance = 0.12 * 0.12 * ray * ray.transpose() + 0.002 * 0.002 * across_ray;
  out.measurement.cameras = 1;
  return out;
}

// From one camera a still spot's depth wanders by more than the 10 cm a ball must travel, and the
// flight fit, judged per axis, is loose along the ray only: the spot is never confirmed, the ball
// flying across the view is, as soon as from two cameras (the newest four points).
TEST(TrackInitiator, OneCamerasViewsConfirmTheFlyingBallNotAStillSpot) {
  TrackInitiator initiator;
  std::mt19937 rng(11);
  std::optional<int> confirmed_at;
  for (int k = 0; k < 120; ++k) {
    const double t = k / kRate;
    std::vector<TrackletPoint> candidates{
        OneCameraPoint(k, Eigen::Vector3d(1.2, 0.4, 0.1), &rng, 0)};
    // The ball from k = 60 on, at 8 m/s along the table.
    if (k >= 60) {
      const double s = t - 0.5;
      candidates.push_back(OneCameraPoint(
          k, Eigen::Vector3d(-1.2 + 8.0 * s, 0.1, 0.2 + 1.5 * s - 4.9 * s * s), &rng, 1));
    }
    if (auto confirmed = initiator.Push(FromSeconds(t), candidates)) {
      ASSERT_EQ(confirmed->points.back().detections, std::vector<int>{1}) << k;
      confirmed_at = k;
      break;
    }
  }
  ASSERT_TRUE(confirmed_at.has_value());
  EXPECT_LE(*confirmed_at, 60 + 5);
}

TEST(TrackInitiator, ABounceBreaksTheChainAndTheFlightAfterItIsConfirmedAgain) {
  TrackInitiator initiator;
  // Down at 3 m/s onto the table at k = 0, up at 2.5 m/s after it; 4 m/s along x.
  const auto ball = [](int k) {
    const double t = k / kRate;
    return Eigen::Vector3d(4.0 * t, 0.0, 0.02 + (k < 0 ? -3.0 * t : 2.5 * t) - 4.9 * t * t);
  };
  std::vector<std::pair<int, int>> confirmed;  // (first, last) set of each confirmed tracklet
  for (int k = -8; k < 8; ++k) {
    const std::vector<TrackletPoint> candidates = {Point(k + 8, ball(k), 0)};
    if (const auto c = initiator.Push(FromSeconds((k + 8) / kRate), candidates)) {
      confirmed.emplace_back(
          static_cast<int>(std::lround(ToSeconds(c->points.front().t) * kRate)) - 8, k);
    }
  }
  // The ball keeps being confirmed while it flies (the tracker takes no notice then); no
  // tracklet spans the bounce, and one after it is confirmed within 4 points.
  ASSERT_GE(confirmed.size(), 2u);
  EXPECT_EQ(confirmed.front(), std::make_pair(-8, -5));
  bool after = false;
  for (const auto& [first, last] : confirmed) {
    EXPECT_TRUE(last < 0 || first >= 0) << first << ".." << last;
    if (first >= 0 && last <= 4) after = true;
  }
  EXPECT_TRUE(after);
}

// A serve toss seen only around its top (a hand hid its rise): it travels less than 10 cm in a
// quarter of a second but falls with gravity's curvature, which confirms it; a lamp measured with
// the same noise does not fall.
TEST(TrackInitiator, ATossNearItsTopIsConfirmedByItsFall) {
  TrackInitiator initiator;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::optional<int> confirmed_at;
  for (int k = 0; k < 30 && !confirmed_at; ++k) {
    const double t = (k - 12) / kRate;  // the top at k = 12
    const Eigen::Vector3d toss(-1.6 + noise(rng), 0.2 + noise(rng), 0.3 - 4.9 * t * t + noise(rng));
    const Eigen::Vector3d lamp(1.0 + noise(rng), -0.4 + noise(rng), 0.6 + noise(rng));
    const std::vector<TrackletPoint> candidates = {Point(k, toss, 0), Point(k, lamp, 1)};
    if (const auto c = initiator.Push(FromSeconds(k / kRate), candidates)) {
      EXPECT_EQ(c->points.back().detections, std::vector<int>{0});
      confirmed_at = k;
    }
  }
  ASSERT_TRUE(confirmed_at.has_value());
  // 0.1 s of points (13 at 120 per second) are needed for the curvature to show.
  EXPECT_GE(*confirmed_at, 12);
  EXPECT_LE(*confirmed_at, 16);
}

// Points at 25 sets per second (a webcam) of the drive above, 1 cm of noise (a 640x480 view).
std::vector<TrackletPoint> WebcamPoints(int n, bool streak, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<TrackletPoint> out;
  for (int k = 0; k < n; ++k) {
    const double t = k / 25.0;
    TrackletPoint p = PointAt(t,
                              Eigen::Vector3d(-1.2 + 8.0 * t + noise(*rng), 0.1 + noise(*rng),
                                              0.2 + 1.5 * t - 4.9 * t * t + noise(*rng)),
                              0.01, 1);
    p.streak = streak;
    out.push_back(p);
  }
  return out;
}

TEST(TrackInitiator, ThreeStreaksOfAWebcamConfirmAFlightThreePlainPointsDoNot) {
  // Three frames of 25 fps span 80 ms, as six at 60 fps; seen as blur streaks they moved two
  // diameters or more in one exposure: no hand, no lamp.
  for (const bool streak : {true, false}) {
    std::mt19937 rng(11);
    TrackInitiator initiator;
    std::optional<Tracklet> confirmed;
    for (const TrackletPoint& p : WebcamPoints(3, streak, &rng)) {
      confirmed = initiator.Push(p.t, std::vector<TrackletPoint>{p});
    }
    EXPECT_EQ(confirmed.has_value(), streak) << (streak ? "streaks" : "plain points");
  }
  // The fourth plain point confirms.
  std::mt19937 rng(11);
  TrackInitiator initiator;
  std::optional<Tracklet> confirmed;
  for (const TrackletPoint& p : WebcamPoints(4, false, &rng)) {
    confirmed = initiator.Push(p.t, std::vector<TrackletPoint>{p});
  }
  EXPECT_TRUE(confirmed.has_value());
}

TEST(TrackInitiator, StreaksThatDoNotShowTheBallsColourCountForNothing) {
  // Webcam tuning 18: a hand over a brown floor, a faint streak in two cameras for three frames
  // (FrameSetOptions::off_colour_residual). Three streaks of it confirm nothing, however many
  // follow; three of the ball do, and one off-colour point among them delays the confirmation
  // by a frame.
  const auto confirmed_at = [](int points, int off_from, int off_count) -> std::optional<int> {
    std::mt19937 rng(11);
    TrackInitiator initiator;
    const auto all = WebcamPoints(points, true, &rng);
    for (int k = 0; k < points; ++k) {
      TrackletPoint p = all[k];
      p.off_colour = k >= off_from && k < off_from + off_count;
      if (initiator.Push(p.t, std::vector<TrackletPoint>{p})) return k;
    }
    return std::nullopt;
  };
  EXPECT_EQ(confirmed_at(3, 0, 0), 2);
  EXPECT_FALSE(confirmed_at(3, 0, 3).has_value());
  EXPECT_FALSE(confirmed_at(6, 0, 6).has_value());  // however long it runs
  EXPECT_EQ(confirmed_at(6, 0, 1), 3);              // three that count, from the fourth
}

// A webcam that misses the ball in a frame or two: 80-120 ms between two points at 25 fps,
// longer than max_gap_s (70 ms); the gap is counted in the sets' own period, so the tracklet
// waits for max_missed missed sets (and no more) whatever the rate. Points of one view (one
// camera, placed along the ray by the diameter) wait for one.
TEST(TrackInitiator, AWebcamThatMissesAFrameOrTwoKeepsItsTracklet) {
  for (const int cameras : {2, 1}) {
    for (const int missed : {1, 2, 3}) {
      std::mt19937 rng(5);
      TrackInitiator initiator;
      std::optional<Tracklet> confirmed;
      std::vector<TrackletPoint> points = WebcamPoints(4 + missed, false, &rng);
      for (TrackletPoint& p : points) p.measurement.cameras = cameras;
      for (int k = 0; k < static_cast<int>(points.size()); ++k) {
        const bool seen = k < 2 || k >= 2 + missed;  // frames 2.. missed
        confirmed = initiator.Push(points[k].t, seen ? std::vector<TrackletPoint>{points[k]}
                                                     : std::vector<TrackletPoint>{});
      }
      const int waits = cameras >= 2 ? TrackInitiatorOptions{}.max_missed
                                     : TrackInitiatorOptions{}.max_missed_one_view;
      EXPECT_EQ(confirmed.has_value(), missed <= waits)
          << cameras << " camera(s), " << missed << " frame(s) missed";
    }
  }
}

// A toss at 25 fps near its top travels little: its fall confirms it, but only from 6 points (a
// parabola's 3 parameters and 3 more): through 4 points of a hand or a shirt's edge a parabola
// with g's curvature is found by chance (two time-stamps of a 25 fps camera take 0.12 s).
TEST(TrackInitiator, ASlowTossAt25FpsIsConfirmedByItsFallFromItsSixthPoint) {
  TrackInitiator initiator;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.003);
  std::optional<int> confirmed_at;
  for (int k = 0; k < 12 && !confirmed_at; ++k) {
    const double t = (k - 3) / 25.0;  // the top at k = 3
    const TrackletPoint p = PointAt(
        k / 25.0,
        Eigen::Vector3d(-2.3 + noise(rng), 0.1 + noise(rng), 0.4 - 4.9 * t * t + noise(rng)), 0.01,
        1);
    if (initiator.Push(p.t, std::vector<TrackletPoint>{p})) confirmed_at = k;
  }
  ASSERT_TRUE(confirmed_at.has_value());
  EXPECT_EQ(*confirmed_at, 5);  // its sixth point (it has fallen 8 cm by then: no travel yet)
}

// A serve's toss seen at 25 fps with 3 mm of noise, its first `points`: launched at `launch` m/s
// from 0.1 m above the table's level, `lean` m sideways for every metre up (or, `gravity` false,
// lifted at that speed steadily). The frame it is confirmed at, if any.
std::optional<int> ConfirmedRise(double launch, bool gravity, double lean, int points,
                                 const TrackInitiatorOptions& options = {}) {
  TrackInitiator initiator(options);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.003);
  for (int k = 0; k < points; ++k) {
    const double t = k / 25.0;
    const double rise = launch * t - (gravity ? 4.9 * t * t : 0.0);
    const TrackletPoint p = PointAt(
        t,
        Eigen::Vector3d(-1.5 + lean * rise + noise(rng), 0.2 + noise(rng), 0.1 + rise + noise(rng)),
        0.003, 1);
    if (initiator.Push(p.t, std::vector<TrackletPoint>{p})) return k;
  }
  return std::nullopt;
}

TEST(TrackInitiator, ASlowTossRisingAt25FpsIsConfirmedFromItsFourthPoint) {
  // Launched at 2.0 m/s: its first 4 points average 1.41 m/s (under min_travel_speed) over 17
  // cm; before toss_max_lean it waited for 6 points of its fall (0.24 s later at best).
  const auto at = ConfirmedRise(2.0, true, 0.0, 8);
  ASSERT_TRUE(at.has_value());
  EXPECT_EQ(*at, 3);
  TrackInitiatorOptions off;
  off.toss_max_lean = 0.0;
  EXPECT_FALSE(ConfirmedRise(2.0, true, 0.0, 4, off).has_value());
}

TEST(TrackInitiator, ASlantedSlowRiseIsNoToss) {
  // Rising as slowly but 39 degrees off the vertical (an arm's swing): not in its first 5
  // points (its 6th, 0.2 s in, confirms it by its fall, as any slow flight).
  EXPECT_FALSE(ConfirmedRise(1.5, true, 0.8, 5).has_value());
  EXPECT_TRUE(ConfirmedRise(1.5, true, 0.0, 5).has_value());
  // A known limit: over 4 points at 25 fps a flight with gravity's pull and a steady lift differ
  // by 4 mm RMS, within the fit's tolerance: a hand lifted 10 cm straight up at 1.4 m/s is
  // confirmed too (the filter then ends its track after slow_window_s: it does not fall).
  EXPECT_TRUE(ConfirmedRise(1.4, false, 0.0, 5).has_value());
}

// The top edge of a player's ball-coloured shorts, paired across two cameras (sports tuning scene
// 23 at 5.08-5.18 s, as measured): the pieces the colour split off jump by 5-10 cm sideways while
// their heights, by chance, rise and fall with nearly gravity's curvature, and the newest four lie
// on one line. Its heights alone would confirm it as a toss near its top; no flight passes through
// all its points (the sideways jumps), and a ball's fall is a flight in all three axes.
TEST(TrackInitiator, AShirtsEdgeWhoseHeightsHappenToFallIsNoToss) {
  const double ts[] = {5.075, 5.1, 5.1083, 5.1167, 5.125, 5.1333, 5.15, 5.1667, 5.1833};
  const Eigen::Vector3d ps[] = {
      {-2.280, 0.449, 0.141}, {-2.221, 0.375, 0.167}, {-2.219, 0.384, 0.168},
      {-2.210, 0.386, 0.172}, {-2.211, 0.389, 0.169}, {-2.248, 0.443, 0.151},
      {-2.262, 0.494, 0.151}, {-2.246, 0.500, 0.157}, {-2.245, 0.508, 0.159}};
  TrackInitiator initiator;
  for (int k = 0; k < 9; ++k) {
    const TrackletPoint p = PointAt(ts[k], ps[k], 0.0048, 1);
    EXPECT_FALSE(initiator.Push(p.t, std::vector<TrackletPoint>{p}).has_value()) << ts[k];
  }
}

TEST(TrackInitiator, AJerkyPathFitsNoFlight) {
  // At 25 sets per second, 1 cm of noise: a speck on a player that jumps on, stops and jumps
  // again, at a constant height. Each point lies within the wide gate of the two before it, and
  // it travels 21 cm at 1.8 m/s, but no flight passes through all four (2.7 cm RMS from the
  // best, 2.5 cm allowed); without the flight fit it would be confirmed.
  for (const bool fit : {true, false}) {
    TrackInitiatorOptions options;
    if (!fit) options.fit_tolerance = 1e3;
    TrackInitiator initiator(options);
    std::optional<Tracklet> confirmed;
    const double ys[] = {0.0, 0.10, 0.095, 0.215};
    for (int k = 0; k < 4; ++k) {
      const TrackletPoint p = PointAt(k * 0.04, Eigen::Vector3d(-2.3, ys[k], 0.4), 0.01, 1);
      confirmed = initiator.Push(p.t, std::vector<TrackletPoint>{p});
    }
    EXPECT_EQ(confirmed.has_value(), !fit) << (fit ? "with" : "without") << " the flight fit";
  }
}

TEST(TrackInitiator, ValidatesItsOptions) {
  TrackInitiatorOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.confirm_points = 1;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.max_span_s = o.max_gap_s;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("span"), std::string::npos);
  o = {};
  o.min_confirm_points = o.confirm_points + 1;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.fit_tolerance = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.toss_max_lean = -0.1;
  EXPECT_FALSE(o.IsValid(&why));
}

FrameSetResult Result(int k, bool tentative) {
  FrameSetResult r;
  r.t = FromSeconds(k / kRate);
  if (tentative) {
    r.measurement = Measurement{};
    r.tentative = true;
  }
  r.detections = {Detection{0, {1.0, 2.0}, 5.0, 20, false},
                  Detection{1, {3.0, 4.0}, 5.0, 20, false}};
  return r;
}

TEST(ResultHold, RevisionsReachHeldRowsAndTentativeOnesLoseTheirMeasurement) {
  ResultHold hold(0.25);
  std::vector<FrameSetResult> out;
  const auto push = [&](FrameSetResult r) {
    for (auto& f : hold.Push(std::move(r))) out.push_back(std::move(f));
  };
  // 60 tentative sets; the 40th confirms 37-39.
  for (int k = 0; k < 60; ++k) {
    FrameSetResult r = Result(k, true);
    if (k == 40) {
      r.tentative = false;
      for (int i = 37; i < 40; ++i) {
        Revision rev;
        rev.t = FromSeconds(i / kRate);
        rev.measurement.cameras = 2;
        rev.state.measured = true;
        rev.accepted = {1};
        r.revisions.push_back(rev);
      }
    }
    push(std::move(r));
  }
  // 0.25 s at 120 per second: 30 sets held, the rest out, in order.
  ASSERT_EQ(out.size(), 29u);
  for (auto& f : hold.Flush()) out.push_back(std::move(f));
  ASSERT_EQ(out.size(), 60u);
  EXPECT_EQ(hold.revised(), 3);
  EXPECT_EQ(hold.missed(), 0);
  for (int k = 0; k < 60; ++k) {
    const FrameSetResult& r = out[k];
    EXPECT_EQ(r.t, FromSeconds(k / kRate));
    EXPECT_FALSE(r.tentative);
    const bool revised = k >= 37 && k <= 40;
    EXPECT_EQ(r.measurement.has_value(), revised) << k;
    EXPECT_EQ(r.state.has_value(), revised && k < 40) << k;
    EXPECT_EQ(r.detections[1].accepted, revised && k < 40) << k;
  }
}

// A lone view the track took waits with a measured state (FrameSetOptions::lone_view_depth_sigma):
// never placed, it leaves as the filter's state without a measurement; placed, as its revision.
TEST(ResultHold, AWaitingLoneViewLeavesAsAMeasurementOnlyWhenPlaced) {
  ResultHold hold(0.25);
  std::vector<FrameSetResult> out;
  for (int k = 0; k < 40; ++k) {
    FrameSetResult r = Result(k, k == 5 || k == 6);
    if (r.tentative) {
      r.measurement->cameras = 1;
      r.state = TrackedState{r.t, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), true, 1, 0.0};
    }
    if (k == 8) {
      Revision placed;
      placed.t = FromSeconds(6 / kRate);
      placed.measurement.cameras = 1;
      placed.state.measured = true;
      placed.state.cameras = 1;
      placed.accepted = {0};
      r.revisions.push_back(placed);
    }
    for (auto& f : hold.Push(std::move(r))) out.push_back(std::move(f));
  }
  ASSERT_GT(out.size(), 6u);
  ASSERT_TRUE(out[5].state.has_value());
  EXPECT_FALSE(out[5].measurement.has_value());
  EXPECT_FALSE(out[5].state->measured);
  EXPECT_EQ(out[5].state->cameras, 0);
  ASSERT_TRUE(out[6].measurement.has_value());
  EXPECT_TRUE(out[6].state->measured);
  EXPECT_EQ(out[6].state->cameras, 1);
  EXPECT_TRUE(out[6].detections[0].accepted);
}

}  // namespace
}  // namespace p4::track
