#include "p4/track/stroke_fit.h"

#include <gtest/gtest.h>

#include <random>

#include "p4/sim/ball_physics.h"

namespace p4::track {
namespace {

const Eigen::Vector3d kCamera(0.3, -3.6, 1.4);  // beside the table, 4 m from the ball

struct Flight {
  std::vector<std::vector<BearingObservation>> pieces;  // cut at the table contacts
  std::vector<std::vector<Eigen::Vector3d>> truth;      // ball centre at each observation
  std::vector<sim::ContactEvent> contacts;
};

// The simulator's ball (drag, Magnus, a bounce that trades spin for speed) seen at 120 Hz from
// one side camera (f = 1000 px): bearings with 0.3 px of noise, distances from the diameter with
// 3 % (a 10 px ball measured to 0.3 px).
Flight Simulate(const sim::BallState& start, double duration, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> pixel(0.0, 0.3 / 1000.0), scale(0.0, 0.03);
  sim::BallState s = start;
  const sim::BallParams params;
  Flight flight;
  flight.pieces.emplace_back();
  flight.truth.emplace_back();
  double t = 0.0, next = 0.0;
  while (t < duration) {
    if (t >= next - 1e-12) {
      BearingObservation o;
      o.t = t;
      o.origin = kCamera;
      const Eigen::Vector3d d = (s.position - kCamera).normalized();
      const Eigen::Vector3d e1 = d.unitOrthogonal(), e2 = d.cross(e1);
      o.direction = (d + pixel(rng) * e1 + pixel(rng) * e2).normalized();
      o.angle_sigma = 0.3 / 1000.0;
      o.distance = (s.position - kCamera).norm() * (1.0 + scale(rng));
      o.distance_sigma = 0.03 * o.distance;
      flight.pieces.back().push_back(o);
      flight.truth.back().push_back(s.position);
      next += 1.0 / 120.0;
    }
    const sim::ContactEvent e = sim::WorldStep(&s, t, 0.0002, params);
    t += 0.0002;
    if (e.kind != sim::Contact::kNone) {
      EXPECT_EQ(e.kind, sim::Contact::kTable) << "the test's flight must touch nothing else";
      flight.contacts.push_back(e);
      flight.pieces.emplace_back();
      flight.truth.emplace_back();
    }
  }
  return flight;
}

// A starting point as a caller has one: each piece's quadratic fit, contacts midway between the
// views around them, on the table below the ray.
Stroke Guess(const Flight& flight) {
  Stroke guess;
  for (const auto& obs : flight.pieces) {
    guess.pieces.push_back(QuadraticPiece(obs));
  }
  for (size_t i = 0; i + 1 < flight.pieces.size(); ++i) {
    const BearingObservation& o = flight.pieces[i].back();
    Junction c;
    c.t = 0.5 * (o.t + flight.pieces[i + 1].front().t);
    const double s = (0.02 - o.origin.z()) / o.direction.z();
    c.point = o.origin + s * o.direction;
    c.on_plane = true;
    guess.junctions.push_back(c);
  }
  return guess;
}

double RmsError(const Stroke& stroke, const Flight& flight, double* worst) {
  double sum = 0.0;
  int n = 0;
  *worst = 0.0;
  for (size_t i = 0; i < flight.pieces.size(); ++i) {
    for (size_t k = 0; k < flight.pieces[i].size(); ++k) {
      const Vector6d x = StrokeStateAt(stroke, flight.pieces[i][k].t, FlightModel{});
      const double e = (x.head<3>() - flight.truth[i][k]).norm();
      sum += e * e, ++n;
      *worst = std::max(*worst, e);
    }
  }
  return std::sqrt(sum / n);
}

// A topspin drive (60 rev/s) from behind the end line to the far half and up again: the spin
// changes at the bounce. The diameters alone place the ball to ~120 mm per frame.
TEST(StrokeFit, TableContactAndSpinFixTheDepthOfATopspinDrive) {
  sim::BallState s;
  s.position = {-1.6, 0.2, 0.3};
  s.velocity = {8.0, 0.3, 1.8};
  s.spin = {0.0, 2 * M_PI * 60.0, 0.0};  // topspin for a ball flying to +x
  const Flight flight = Simulate(s, 0.5, 7);
  ASSERT_EQ(flight.contacts.size(), 1u);
  ASSERT_GE(flight.pieces[1].size(), 8u);
  const auto fit = FitStroke(flight.pieces, Guess(flight), StrokeFitOptions{});
  ASSERT_TRUE(fit.has_value());
  double worst = 0.0;
  const double rms = RmsError(*fit, flight, &worst);
  std::printf("stroke fit: rms %.1f mm, worst %.1f mm, bearings %.2f sigma\n", 1e3 * rms,
              1e3 * worst, fit->rms_bearing);
  EXPECT_LT(rms, 0.015);
  EXPECT_LT(worst, 0.040);
  EXPECT_LT(fit->rms_bearing, 1.5);
  // The contact is found where the ball touched, to a few millimetres and a fraction of a frame.
  EXPECT_NEAR(fit->junctions[0].t, flight.contacts[0].time, 0.002);
  EXPECT_LT((fit->junctions[0].point - flight.contacts[0].point).norm(), 0.02);
}

// Without a contact (a flight that ends before the bounce) the diameters and gravity still
// average to a few centimetres over the piece, far better than one frame's ~120 mm.
TEST(StrokeFit, OnePieceWithoutContactAveragesTheDiameters) {
  sim::BallState s;
  s.position = {-1.6, 0.2, 0.3};
  s.velocity = {8.0, 0.3, 1.8};
  s.spin = {0.0, 2 * M_PI * 60.0, 0.0};
  const Flight flight = Simulate(s, 0.3, 11);
  ASSERT_EQ(flight.pieces.size(), 1u);
  const auto fit = FitStroke(flight.pieces, Guess(flight), StrokeFitOptions{});
  ASSERT_TRUE(fit.has_value());
  double worst = 0.0;
  const double rms = RmsError(*fit, flight, &worst);
  std::printf("one piece: rms %.1f mm, worst %.1f mm\n", 1e3 * rms, 1e3 * worst);
  EXPECT_LT(rms, 0.020);
}

TEST(StrokeFit, RefusesMismatchedInput) {
  const std::vector<std::vector<BearingObservation>> two(2, std::vector<BearingObservation>(5));
  Stroke guess;
  guess.pieces.resize(2);  // but no junction between them
  EXPECT_FALSE(FitStroke(two, guess, StrokeFitOptions{}).has_value());
  guess.junctions.resize(1);
  const std::vector<std::vector<BearingObservation>> short_piece{
      std::vector<BearingObservation>(2), std::vector<BearingObservation>(5)};
  EXPECT_FALSE(FitStroke(short_piece, guess, StrokeFitOptions{}).has_value());
  std::string why;
  StrokeFitOptions bad;
  bad.contact_sigma = 0.0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_FALSE(why.empty());
}

}  // namespace
}  // namespace p4::track
