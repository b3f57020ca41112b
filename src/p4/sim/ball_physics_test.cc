#include "p4/sim/ball_physics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "p4/core/table.h"

namespace p4::sim {
namespace {

double Energy(const BallState& s, const BallParams& p) {
  const double inertia = 2.0 / 3.0 * p.mass * p.radius * p.radius;
  return 0.5 * p.mass * s.velocity.squaredNorm() + 0.5 * inertia * s.spin.squaredNorm() +
         p.mass * p.gravity * s.position.z();
}

// Flies until the next contact of `kind` or `max_t`; returns the contact (kNone if none).
ContactEvent FlyUntil(BallState* s, Contact kind, double max_t, const BallParams& p,
                      double* apex = nullptr) {
  double t = 0.0;
  while (t < max_t) {
    ContactEvent e = WorldStep(s, t, 0.0005, p);
    t += 0.0005;
    if (apex) *apex = std::max(*apex, s->position.z());
    if (e.kind == kind) return e;
  }
  return {};
}

TEST(BallPhysics, DroppedFrom30cmBouncesToAbout23cm) {
  const BallParams p;
  BallState s;
  s.position = {0.5, 0.2, 0.30 + p.radius};  // the ball's bottom 30 cm above the table
  const ContactEvent bounce = FlyUntil(&s, Contact::kTable, 2.0, p);
  ASSERT_EQ(bounce.kind, Contact::kTable);
  EXPECT_NEAR(bounce.before.position.z(), p.radius, 1e-6);
  double apex = 0.0;
  FlyUntil(&s, Contact::kTable, 2.0, p, &apex);
  const double rebound = apex - p.radius;
  EXPECT_NEAR(rebound, 0.235, 0.01);  // ITTF 2.3: 23-25 cm
  // Drag takes its share: without it the ball comes higher.
  BallParams no_drag = p;
  no_drag.drag_kd = 0.0;
  BallState t;
  t.position = {0.5, 0.2, 0.30 + p.radius};
  FlyUntil(&t, Contact::kTable, 2.0, no_drag);
  double apex_no_drag = 0.0;
  FlyUntil(&t, Contact::kTable, 2.0, no_drag, &apex_no_drag);
  EXPECT_GT(apex_no_drag - p.radius, rebound + 0.005);
}

TEST(BallPhysics, BounceTimeIsExactWithoutDrag) {
  BallParams p;
  p.drag_kd = 0.0;
  BallState s;
  s.position = {0.5, 0.3, 0.5 + p.radius};
  const ContactEvent bounce = FlyUntil(&s, Contact::kTable, 2.0, p);
  ASSERT_EQ(bounce.kind, Contact::kTable);
  EXPECT_NEAR(bounce.time, std::sqrt(2.0 * 0.5 / p.gravity), 2e-6);
  const double e = TableRestitution(bounce.before.velocity.z(), p);
  EXPECT_NEAR(bounce.after.velocity.z(), -e * bounce.before.velocity.z(), 1e-9);
  EXPECT_NEAR(TableRestitution(4.0, p), 0.88, 1e-12);
  EXPECT_GT(TableRestitution(2.0, p), TableRestitution(6.0, p));
}

TEST(BallPhysics, ABounceKeepsEnergyBelowOne) {
  const BallParams p;
  for (double vx : {-12.0, -3.0, 0.0, 4.0, 15.0}) {
    for (double spin_rps : {-150.0, -40.0, 0.0, 60.0, 150.0}) {
      BallState s;
      s.position = {0.0, 0.0, p.radius};
      s.velocity = {vx, 1.0, -4.0};
      s.spin = {10.0, 2.0 * M_PI * spin_rps, 30.0};
      const BallState out =
          Impact(s, Eigen::Vector3d::UnitZ(), p.table_restitution, p.table_friction, p);
      EXPECT_LT(Energy(out, p), Energy(s, p)) << vx << " " << spin_rps;
      EXPECT_GT(out.velocity.z(), 0.0);
    }
  }
}

TEST(BallPhysics, TopspinKicksForwardAndBackspinChecks) {
  const BallParams p;
  BallState top;
  top.position = {0.0, 0.0, p.radius};
  top.velocity = {5.0, 0.0, -3.0};
  top.spin = {0.0, 2.0 * M_PI * 100.0, 0.0};  // topspin for a ball moving +x
  BallState back = top;
  back.spin = -top.spin;
  const auto n = Eigen::Vector3d::UnitZ();
  const BallState top_out = Impact(top, n, p.table_restitution, p.table_friction, p);
  const BallState back_out = Impact(back, n, p.table_restitution, p.table_friction, p);
  EXPECT_GT(top_out.velocity.x(), 5.0);
  EXPECT_LT(back_out.velocity.x(), 5.0);
}

TEST(BallPhysics, DragSlowsTheBall) {
  BallParams with_drag;
  BallParams no_drag;
  no_drag.drag_kd = 0.0;
  BallState a;
  a.position = {-1.5, 0.0, 0.3};
  a.velocity = {15.0, 0.0, 1.0};
  BallState b = a;
  for (int i = 0; i < 200; ++i) {  // 0.1 s
    a = FlightStep(a, 0.0005, with_drag);
    b = FlightStep(b, 0.0005, no_drag);
  }
  EXPECT_NEAR(b.velocity.x(), 15.0, 1e-9);
  // a = k/m v^2 = 0.1407 * 225 = 31.7 m/s^2 at the start: ~2.5 m/s lost in 0.1 s.
  EXPECT_LT(a.velocity.x(), 13.0);
  EXPECT_GT(a.velocity.x(), 12.0);
}

TEST(BallPhysics, MagnusCurvesTheRightWay) {
  const BallParams p;
  BallState plain;
  plain.position = {-1.5, 0.0, 0.3};
  plain.velocity = {10.0, 0.0, 1.0};
  BallState top = plain, back = plain, side = plain;
  top.spin = {0.0, 2.0 * M_PI * 100.0, 0.0};   // topspin: dips
  back.spin = -top.spin;                       // backspin: floats
  side.spin = {0.0, 0.0, 2.0 * M_PI * 100.0};  // spin about +z: curves to +y (w x v = +y)
  for (int i = 0; i < 300; ++i) {
    plain = FlightStep(plain, 0.0005, p);
    top = FlightStep(top, 0.0005, p);
    back = FlightStep(back, 0.0005, p);
    side = FlightStep(side, 0.0005, p);
  }
  EXPECT_LT(top.position.z(), plain.position.z() - 0.02);
  EXPECT_GT(back.position.z(), plain.position.z() + 0.02);
  EXPECT_GT(side.position.y(), 0.02);
  EXPECT_NEAR(plain.position.y(), 0.0, 1e-12);
}

TEST(BallPhysics, ABallIntoTheNetDropsOnItsOwnSide) {
  const BallParams p;
  BallState s;
  s.position = {-1.0, 0.1, 0.12};
  s.velocity = {8.0, 0.0, 0.0};
  const ContactEvent net = FlyUntil(&s, Contact::kNet, 1.0, p);
  ASSERT_EQ(net.kind, Contact::kNet);
  EXPECT_NEAR(net.point.x(), -p.radius, 1e-4);
  EXPECT_LT(net.after.velocity.x(), 0.0);
  EXPECT_GT(net.after.velocity.x(), -2.0);
  const ContactEvent next = FlyUntil(&s, Contact::kTable, 1.0, p);
  ASSERT_EQ(next.kind, Contact::kTable);
  EXPECT_LT(next.point.x(), 0.0);
}

TEST(BallPhysics, ABallThatClipsTheCordSlowsAndGoesOn) {
  const BallParams p;
  BallState s;
  s.position = {-1.0, 0.1, table::kNetHeight + p.radius - 0.004};
  s.velocity = {8.0, 0.0, 0.0};
  BallParams no_gravity = p;
  no_gravity.gravity = 0.0;
  const ContactEvent net = FlyUntil(&s, Contact::kNet, 1.0, no_gravity);
  ASSERT_EQ(net.kind, Contact::kNet);
  EXPECT_GT(net.after.velocity.z(), 0.0);  // deflected up off the cord
  EXPECT_GT(net.after.velocity.x(), 0.0);  // and still going over
}

TEST(BallPhysics, FloorStopsTheFall) {
  const BallParams p;
  BallState s;
  s.position = {2.0, 0.0, 0.5};
  const ContactEvent floor = FlyUntil(&s, Contact::kFloor, 2.0, p);
  ASSERT_EQ(floor.kind, Contact::kFloor);
  EXPECT_NEAR(floor.before.position.z(), table::kFloorZ + p.radius, 1e-6);
  std::string error;
  EXPECT_TRUE(p.IsValid(&error));
  BallParams bad = p;
  bad.table_restitution = 1.2;
  EXPECT_FALSE(bad.IsValid(&error));
}

}  // namespace
}  // namespace p4::sim
