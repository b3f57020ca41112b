#include "p4/track/flight_check.h"

#include <gtest/gtest.h>

#include <functional>
#include <vector>

namespace p4::track {
namespace {

constexpr double kFps = 60.0;

// A measured row at time k / kFps.
FrameSetResult Row(int k, const Eigen::Vector3d& p) {
  FrameSetResult r;
  r.t = FromSeconds(k / kFps);
  Measurement m;
  m.position = p;
  m.cameras = 2;
  r.measurement = m;
  TrackedState s;
  s.t = r.t;
  s.position = p;
  s.measured = true;
  s.cameras = 2;
  r.state = s;
  return r;
}

// Every row pushed, then flushed: the output in time order.
std::vector<FrameSetResult> Check(const std::vector<FrameSetResult>& rows, int* dropped) {
  FlightCheck check{FlightCheckOptions{}};
  std::vector<FrameSetResult> out;
  for (const auto& r : rows) {
    for (auto& o : check.Push(r)) out.push_back(std::move(o));
  }
  for (auto& o : check.Flush()) out.push_back(std::move(o));
  *dropped = check.dropped();
  return out;
}

// The ball under gravity alone (no drag: the check's model is not the world's), from p0 with v0.
Eigen::Vector3d Ballistic(const Eigen::Vector3d& p0, const Eigen::Vector3d& v0, double t) {
  return p0 + t * v0 + 0.5 * t * t * Eigen::Vector3d(0.0, 0.0, -9.81);
}

// 60 rows (1 s, past the check's hold of 0.5 s: rows are judged as they come, not all at the end)
// of a flight from x = -1.2 m, 25 cm over the table.
std::vector<FrameSetResult> Flight(const std::function<Eigen::Vector3d(double)>& at = [](double t) {
  return Ballistic({-1.2, 0.1, 0.25}, {6.0, -0.5, 1.5}, t);
}) {
  constexpr int kRows = 60;
  std::vector<FrameSetResult> rows;
  rows.reserve(kRows);
  for (int k = 0; k < kRows; ++k) rows.push_back(Row(k, at(k / kFps)));
  return rows;
}

TEST(FlightCheck, DropsARowOffTheFlightOnBothSides) {
  std::vector<FrameSetResult> rows = Flight();
  const Eigen::Vector3d truth = rows[20].measurement->position;
  // A wrong pair of views for one time-stamp: 15 cm beside the ball.
  rows[20].measurement->position += Eigen::Vector3d(0.0, 0.15, -0.03);
  rows[20].state->position = rows[20].measurement->position;
  int dropped = 0;
  const auto out = Check(rows, &dropped);
  ASSERT_EQ(out.size(), rows.size());
  EXPECT_EQ(dropped, 1);
  for (size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].t, rows[k].t);
    EXPECT_EQ(out[k].measurement.has_value(), k != 20) << k;
  }
  ASSERT_TRUE(out[20].state.has_value());
  EXPECT_FALSE(out[20].state->measured);
  // Its state is put back on the flight (drag in the model, none in this world: a few mm).
  EXPECT_LT((out[20].state->position - truth).norm(), 0.005);
}

TEST(FlightCheck, KeepsARowWithinItsNoiseOfTheFlight) {
  std::vector<FrameSetResult> rows = Flight();
  rows[20].measurement->position += Eigen::Vector3d(0.0, 0.03, -0.02);  // 36 mm: under 60 mm
  int dropped = 0;
  const auto out = Check(rows, &dropped);
  EXPECT_EQ(dropped, 0);
  EXPECT_TRUE(out[20].measurement.has_value());
}

TEST(FlightCheck, KeepsTheRowsOfATableBounce) {
  // The ball comes down on the table and leaves it with 0.9 of its vertical speed (the model
  // takes 0.88) and without friction (the model takes some): every row is the ball.
  const Eigen::Vector3d p0(-1.0, 0.0, 0.30), v0(5.0, 0.3, -1.0);
  const double r = 0.02;
  // First contact: z = r.
  const double g = 9.81, a = 0.5 * g, b = -v0.z(), c = -(p0.z() - r);
  const double contact = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const auto at = [&](double t) -> Eigen::Vector3d {
    if (t <= contact) return Ballistic(p0, v0, t);
    const Eigen::Vector3d q = Ballistic(p0, v0, contact);
    Eigen::Vector3d v = v0 + contact * Eigen::Vector3d(0.0, 0.0, -g);
    v.z() = -0.9 * v.z();
    return Ballistic(q, v, t - contact);
  };
  for (int shift = 0; shift < 4; ++shift) {  // the contact at several phases of the frames
    std::vector<FrameSetResult> rows =
        Flight([&](double t) { return at(t + shift / (4.0 * kFps)); });
    int dropped = 0;
    const auto out = Check(rows, &dropped);
    EXPECT_EQ(dropped, 0) << "phase " << shift;
  }
  // A webcam at 25 fps: the first row after the bounce is the last before the ball is hidden
  // for 0.4 s. Only the rows before judge it, through the bounce.
  for (int shift = 0; shift < 4; ++shift) {
    std::vector<FrameSetResult> rows;
    for (int k = 0; k < 30; ++k) {
      const double t = (k + shift / 4.0) / 25.0;
      if (t > contact + 0.04 && t < contact + 0.44) continue;
      rows.push_back(Row(0, at(t)));
      rows.back().t = FromSeconds(t);
    }
    int dropped = 0;
    Check(rows, &dropped);
    EXPECT_EQ(dropped, 0) << "25 fps, phase " << shift;
  }
}

// The ball flies towards player A and is hit back at `hit` s: x speed -7 -> +9 m/s.
std::function<Eigen::Vector3d(double)> HitBackAt(double hit) {
  return [hit](double t) -> Eigen::Vector3d {
    const Eigen::Vector3d p0(-0.5, 0.2, 0.3), v0(-7.0, 0.4, 0.5);
    if (t <= hit) return Ballistic(p0, v0, t);
    return Ballistic(Ballistic(p0, v0, hit), {9.0, -0.6, 1.2}, t - hit);
  };
}

TEST(FlightCheck, KeepsTheRowsOfAHit) {
  const auto at = HitBackAt(0.3);
  for (int shift = 0; shift < 4; ++shift) {
    int dropped = 0;
    Check(Flight([&](double t) { return at(t + shift / (4.0 * kFps)); }), &dropped);
    EXPECT_EQ(dropped, 0) << "phase " << shift;
  }
}

TEST(FlightCheck, LeavesAShortFlightBetweenTwoContactsToTheTracker) {
  // A hit sends the ball back at 15 m/s and 3 rows later the net sends it on (sports tuning 11):
  // no side's flight holds the 3 rows between. As the tracker placed them on their own flight
  // (TrackedState::between_contacts) they are neither judged nor a side; unmarked, they go.
  const double t1 = 20.5 / kFps, t2 = 23.5 / kFps;
  const Eigen::Vector3d p0(-1.2, 0.1, 0.25), v0(6.0, -0.5, 1.5), v_back(-15.0, 0.5, 0.5);
  const Eigen::Vector3d at_hit = Ballistic(p0, v0, t1);
  const Eigen::Vector3d at_net = at_hit + (t2 - t1) * v_back;
  const auto at = [&](double t) -> Eigen::Vector3d {
    if (t < t1) return Ballistic(p0, v0, t);
    if (t < t2) return at_hit + (t - t1) * v_back;
    return Ballistic(at_net, {3.0, 0.5, 1.0}, t - t2);
  };
  for (const bool marked : {true, false}) {
    std::vector<FrameSetResult> rows = Flight(at);
    for (int k = 21; k <= 23; ++k) rows[k].state->between_contacts = marked;
    int dropped = 0;
    const std::vector<FrameSetResult> out = Check(rows, &dropped);
    int kept = 0;
    for (int k = 21; k <= 23; ++k) kept += out[k].measurement.has_value() ? 1 : 0;
    if (marked) {
      EXPECT_EQ(dropped, 0);
      EXPECT_EQ(kept, 3);
    } else {
      EXPECT_GE(dropped, 2);
      EXPECT_LE(kept, 1);
    }
  }
}

TEST(FlightCheck, DropsAWrongLastRowThatNothingAfterConfirms) {
  // The track coasts two sets after its last sighting, then its last row jumps 0.7 m to something
  // else of the ball's colour; no row follows. The wrong row goes, and with it every state after
  // the last sighting: no view confirmed that path.
  std::vector<FrameSetResult> rows = Flight();
  rows.resize(32);
  ClearMeasurement(&rows[30]);
  ClearMeasurement(&rows[31]);
  rows.push_back(Row(32, rows[29].measurement->position + Eigen::Vector3d(-0.7, -0.3, 0.0)));
  int dropped = 0;
  const auto out = Check(rows, &dropped);
  ASSERT_EQ(out.size(), rows.size());
  EXPECT_EQ(dropped, 1);
  for (size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].measurement.has_value(), k < 30) << k;
    EXPECT_EQ(out[k].state.has_value(), k < 30) << k;
  }
}

TEST(FlightCheck, AWrongRowBetweenSightingsKeepsTheGapsFilled) {
  // Sightings, two predicted sets, a wrong row, one predicted set, sightings: the wrong row is
  // a gap between sightings now, and keeps a state on the flight, as do the predicted sets.
  std::vector<FrameSetResult> rows = Flight();
  ClearMeasurement(&rows[18]);
  ClearMeasurement(&rows[19]);
  ClearMeasurement(&rows[21]);
  rows[20].measurement->position += Eigen::Vector3d(0.0, -0.2, 0.05);
  int dropped = 0;
  const auto out = Check(rows, &dropped);
  EXPECT_EQ(dropped, 1);
  for (int k : {18, 19, 20, 21}) {
    EXPECT_FALSE(out[k].measurement.has_value()) << k;
    EXPECT_TRUE(out[k].state.has_value()) << k;
  }
}

TEST(FlightCheck, AWrongFirstRowTakesThePredictionsBeforeTheNextSighting) {
  // A track that starts on a wrong row, predicts one set, then sees the ball: the states before
  // the first sighting go. (The rows before it have no state: another track, or none.)
  std::vector<FrameSetResult> rows = Flight();
  for (int k = 25; k < 28; ++k) rows[k].state.reset(), rows[k].measurement.reset();
  rows[28].measurement->position += Eigen::Vector3d(0.5, 0.3, 0.2);
  ClearMeasurement(&rows[29]);
  int dropped = 0;
  const auto out = Check(rows, &dropped);
  EXPECT_EQ(dropped, 1);
  EXPECT_FALSE(out[28].state.has_value());
  EXPECT_FALSE(out[29].state.has_value());
  EXPECT_TRUE(out[30].measurement.has_value());
  EXPECT_TRUE(out[24].measurement.has_value());
}

TEST(FlightCheck, AWrongRowDoesNotTakeTheGoodRowBeforeItWithIt) {
  // A hit at 0.31 s, then a wrong row at the second time-stamp after it: the first row after the
  // hit is off the flight before it, and its side after holds the wrong row; it stays.
  std::vector<FrameSetResult> rows = Flight(HitBackAt(0.31));
  const int first_after = 19;  // 0.3167 s
  rows[first_after + 1].measurement->position += Eigen::Vector3d(0.4, 0.2, 0.1);
  int dropped = 0;
  const auto out = Check(rows, &dropped);
  EXPECT_EQ(dropped, 1);
  EXPECT_TRUE(out[first_after].measurement.has_value());
  EXPECT_FALSE(out[first_after + 1].measurement.has_value());
}

TEST(FlightCheck, HoldsRowsTwoHorizonsAndReleasesThemInOrder) {
  FlightCheckOptions options;
  FlightCheck check(options);
  const std::vector<FrameSetResult> rows = Flight();
  const int held = static_cast<int>(2 * options.horizon_s * kFps);  // 30 at 60 fps
  std::vector<FrameSetResult> out;
  for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
    for (auto& o : check.Push(rows[k])) out.push_back(std::move(o));
    // Released once 2 horizons old (give or take a row: time-stamps are whole ns).
    EXPECT_NEAR(static_cast<int>(out.size()), std::max(0, k + 1 - held), 1) << k;
  }
  for (auto& o : check.Flush()) out.push_back(std::move(o));
  ASSERT_EQ(out.size(), rows.size());
  for (size_t k = 0; k < out.size(); ++k) EXPECT_EQ(out[k].t, rows[k].t);
}

TEST(FlightCheck, OptionsAreValidated) {
  FlightCheckOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.min_side_rows = 4;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.horizon_s = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.offset_m = -0.01;
  EXPECT_FALSE(o.IsValid(&why));
}

}  // namespace
}  // namespace p4::track
