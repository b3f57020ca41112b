#include "p4/sync/track_2d.h"

#include <gtest/gtest.h>

#include "p4/sync/sync_test_world.h"

namespace p4::sync {
namespace {

TEST(LinkTracks, KeepsTheFlightsAndDropsWhatDoesNotTravel) {
  const testing::Rally rally(6.0, 3);
  testing::Recording r;
  r.seconds = 6.0;
  r.false_candidates = 2;
  const Camera camera = testing::SideCamera();
  const std::vector<Track2d> tracks = LinkTracks(testing::Record(camera, rally, r, 5));
  ASSERT_FALSE(tracks.empty());
  int on_ball = 0, points = 0;
  for (const Track2d& track : tracks) {
    for (const TrackPoint& p : track.points) {
      ++points;
      const auto truth = camera.Project(rally.At(p.t).value_or(Eigen::Vector3d(0, 0, -100)));
      // The lamp (100, 80) never travels; random specks do not last.
      EXPECT_GT((p.pixel - Eigen::Vector2d(100, 80)).norm(), 5.0);
      on_ball += truth && (p.pixel - *truth).norm() < 2.0;
    }
  }
  EXPECT_GE(on_ball, static_cast<int>(0.98 * points)) << on_ball << " of " << points;
  // Most of the ball's frames are in the tracks (a flight's first points may be lost).
  int ball_frames = 0;
  for (double t = 0.0; t < 6.0; t += 1.0 / 60) ball_frames += rally.At(t).has_value();
  EXPECT_GE(on_ball, static_cast<int>(0.9 * ball_frames)) << on_ball << " of " << ball_frames;
}

TEST(LinkTracks, OptionsAreChecked) {
  Track2dOptions options;
  EXPECT_TRUE(options.IsValid(nullptr));
  options.min_points = 1;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("min_points"), std::string::npos);
}

}  // namespace
}  // namespace p4::sync
