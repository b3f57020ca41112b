#include "p4/eval/findable.h"

#include <gtest/gtest.h>

#include <cmath>

#include "p4/core/table.h"
#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

// A grey hall with a little fixed noise, and the ball drawn as a lit orange disc where `camera`
// sees `point` (when `with_ball`).
void Draw(const Camera& camera, const Eigen::Vector3d& point, bool with_ball, I420Image* image) {
  const auto ball = segment::BallColour::Orange().lit;
  const auto centre = camera.Project(point);
  const double radius = table::kBallRadius * camera.fx / (camera.cam_from_world * point).z();
  const int w = image->width(), cw = image->chroma_width();
  for (int y = 0; y < image->height(); ++y) {
    for (int x = 0; x < w; ++x) {
      const bool in = with_ball && centre && std::hypot(x - centre->x(), y - centre->y()) <= radius;
      const int noise = static_cast<int>((x * 7919 + y * 104729) % 5) - 2;
      image->y()[y * w + x] = static_cast<uint8_t>(in ? ball.y : 120 + noise);
      if (x % 2 == 0 && y % 2 == 0) {
        const bool c_in = with_ball && centre &&
                          std::hypot(x + 0.5 - centre->x(), y + 0.5 - centre->y()) <= radius;
        image->u()[(y / 2) * cw + x / 2] = static_cast<uint8_t>(c_in ? ball.u : 128);
        image->v()[(y / 2) * cw + x / 2] = static_cast<uint8_t>(c_in ? ball.v : 128);
      }
    }
  }
}

// Two cameras of the club rig (side, one end).
Rig TwoCameras() {
  Rig rig;
  const auto cameras = testing::ClubCameras();
  rig.cameras = {cameras[0], cameras[2]};
  return rig;
}

// `frames` truth rows at 60 fps, the ball in play from `first_in_play` at 1 m/s over the table.
std::vector<TruthRow> Flight(int frames, int first_in_play) {
  std::vector<TruthRow> truth;
  for (int k = 0; k < frames; ++k) {
    TruthRow row;
    row.t = k / 60.0;
    row.in_play = k >= first_in_play;
    row.velocity = {1.0, 0.0, 0.0};
    row.position = Eigen::Vector3d(-0.5, 0.1, 0.3) + row.t * row.velocity;
    truth.push_back(row);
  }
  return truth;
}

TEST(Findable, CountsFramesWhoseBallStandsOutInEnoughCameras) {
  // Two cameras at 60 fps; the ball in play from frame 20 at 1 m/s over the table; in frames
  // 30-34 camera 1's picture has no ball (hidden, say): those frames are seen by both cameras
  // by the truth, found by one.
  const Rig rig = TwoCameras();
  const std::vector<TruthRow> truth = Flight(60, 20);
  FindableCounter counter(rig, truth, {}, segment::BallColour::Orange(), 0.002);
  I420Image image(1280, 720);
  for (int k = 0; k < 60; ++k) {
    for (int c = 0; c < 2; ++c) {
      const bool hidden = c == 1 && k >= 30 && k < 35;
      Draw(rig.cameras[c], truth[k].position, truth[k].in_play && !hidden, &image);
      counter.Add(c, FromSeconds(truth[k].t), image.View());
    }
  }
  const FindableReport report = counter.Report();
  EXPECT_EQ(report.frames_seen, 40);
  EXPECT_EQ(report.frames_findable, 35);
  EXPECT_NEAR(report.share(), 35.0 / 40.0, 1e-12);
  ASSERT_EQ(report.camera_found.size(), 2u);
  EXPECT_EQ(report.camera_seen[1], 40);
  EXPECT_EQ(report.camera_found[0], 40);
  EXPECT_EQ(report.camera_found[1], 35);
}

TEST(Findable, ABallOfTheHallsColourIsNotFindable) {
  // The same flight over a hall of the ball's own colour (an orange floor): nothing stands out.
  const Rig rig = TwoCameras();
  const std::vector<TruthRow> truth = Flight(30, 10);
  FindableCounter counter(rig, truth, {}, segment::BallColour::Orange(), 0.002);
  I420Image image(1280, 720);
  const auto ball = segment::BallColour::Orange().lit;
  std::fill(image.y(), image.y() + 1280 * 720, static_cast<uint8_t>(ball.y));
  std::fill(image.u(), image.u() + 640 * 360, static_cast<uint8_t>(ball.u));
  std::fill(image.v(), image.v() + 640 * 360, static_cast<uint8_t>(ball.v));
  for (int k = 0; k < 30; ++k) {
    for (int c = 0; c < 2; ++c) counter.Add(c, FromSeconds(truth[k].t), image.View());
  }
  const FindableReport report = counter.Report();
  EXPECT_EQ(report.frames_seen, 20);
  EXPECT_EQ(report.frames_findable, 0);
}

// Two cameras at 60 fps, half the club rig's resolution (640x360: a ball of 4-6 px, the size the
// finder's cells are made for); the ball in play from frame 20, flying at 3.6 m/s across both
// cameras' views (6-9 px a frame), held still from frame `still_from` (the top of a toss, say).
FindableReport StillFrom(int still_from) {
  Rig rig = TwoCameras();
  for (Camera& camera : rig.cameras) {
    camera.width /= 2, camera.height /= 2;
    camera.fx /= 2, camera.fy /= 2;
    camera.cx = (camera.cx + 0.5) / 2 - 0.5, camera.cy = (camera.cy + 0.5) / 2 - 0.5;
  }
  const Eigen::Vector3d velocity(3.0, 2.0, 0.0);
  std::vector<TruthRow> truth;
  for (int k = 0; k < 60; ++k) {
    TruthRow row;
    row.t = k / 60.0;
    row.in_play = k >= 20;
    row.velocity = k < still_from ? velocity : Eigen::Vector3d::Zero();
    row.position = Eigen::Vector3d(-1.2, -0.5, 0.3) + std::min(k, still_from) / 60.0 * velocity;
    truth.push_back(row);
  }
  FindableCounter counter(rig, truth, {}, segment::BallColour::Orange(), 0.002);
  I420Image image(rig.cameras[0].width, rig.cameras[0].height);
  for (int k = 0; k < 60; ++k) {
    for (int c = 0; c < 2; ++c) {
      Draw(rig.cameras[c], truth[k].position, truth[k].in_play, &image);
      counter.Add(c, FromSeconds(truth[k].t), image.View());
    }
  }
  return counter.Report();
}

TEST(Findable, TheWholeImageFinderLosesABallThatStandsStill) {
  // The search that is told where the ball is finds it in all 40 frames either way. The finder,
  // which knows nothing, finds it in most frames while it flies and in none once it has stood
  // still for a frame (its "still" test: what was at one place in the last frame is a lamp, a
  // line or a player's edge), so a ball held still from frame 40 is startable in fewer frames.
  const FindableReport flying = StillFrom(60), held = StillFrom(40);
  for (const FindableReport* report : {&flying, &held}) {
    EXPECT_EQ(report->frames_seen, 40);
    EXPECT_EQ(report->frames_findable, 40);
    ASSERT_EQ(report->camera_started.size(), 2u);
  }
  for (int c = 0; c < 2; ++c) {
    // Flying: most of the 40 frames (the finder's own path in the last frame can take the place
    // where the ball is now: its candidates' middles are cells' centres, 4 px apart).
    EXPECT_GE(flying.camera_started[c], 24) << "camera " << c;
    // Held still for 19 frames: at most its first still frame more than the 20 flying ones.
    EXPECT_LE(held.camera_started[c], 21) << "camera " << c;
    EXPECT_GE(flying.camera_started[c] - held.camera_started[c], 8) << "camera " << c;
  }
  EXPECT_LT(held.frames_startable, flying.frames_startable);
  EXPECT_LE(held.frames_startable, 20);
}

}  // namespace
}  // namespace p4
