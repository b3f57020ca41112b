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

// A dark blue shirt around where `camera` sees `point`: a square of 40 px, but for a disc 7 px
// wider than the ball's radius (a ball held still before a player).
void DrawShirtAround(const Camera& camera, const Eigen::Vector3d& point, I420Image* image) {
  const auto centre = camera.Project(point);
  if (!centre) return;
  const double radius = table::kBallRadius * camera.fx / (camera.cam_from_world * point).z();
  const int w = image->width(), cw = image->chroma_width();
  for (int y = std::max(0, static_cast<int>(centre->y()) - 20);
       y < std::min(image->height(), static_cast<int>(centre->y()) + 20); ++y) {
    for (int x = std::max(0, static_cast<int>(centre->x()) - 20);
         x < std::min(w, static_cast<int>(centre->x()) + 20); ++x) {
      if (std::hypot(x - centre->x(), y - centre->y()) <= radius + 6.0) continue;
      image->y()[y * w + x] = 60;
      image->u()[(y / 2) * cw + x / 2] = 170;
      image->v()[(y / 2) * cw + x / 2] = 110;
    }
  }
}

// Two cameras at 60 fps, half the club rig's resolution (640x360: a ball of 4-6 px, the size the
// finder's cells are made for); the ball in play from frame 20, flying at 3.6 m/s across both
// cameras' views (6-9 px a frame), held still from frame `still_from` (the top of a toss, say),
// before a player's shirt from then when `before_shirt`.
FindableReport StillFrom(int still_from, bool before_shirt = false) {
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
      if (before_shirt && k >= still_from)
        DrawShirtAround(rig.cameras[c], truth[k].position, &image);
      counter.Add(c, FromSeconds(truth[k].t), image.View());
    }
  }
  return counter.Report();
}

TEST(Findable, TheWholeImageFinderKeepsAStillBallOnlyWhereItStandsAlone) {
  // The search that is told where the ball is finds it in all 40 frames each way. The finder,
  // which knows nothing, drops what was at one place in the last frame (a lamp, a line, a
  // player's edge) unless the hall around it is as the background has it: a ball held still
  // from frame 52 in mid-air (the top of a toss) stays startable; held before a player's shirt,
  // it is not. (Held still for longer, the background takes the ball's blocks in as something
  // put down: in 8-10 frames at 60 fps their noise grows past its contrast.)
  const FindableReport flying = StillFrom(60), alone = StillFrom(52),
                       before_shirt = StillFrom(52, true);
  for (const FindableReport* report : {&flying, &alone, &before_shirt}) {
    EXPECT_EQ(report->frames_seen, 40);
    EXPECT_EQ(report->frames_findable, 40);
    ASSERT_EQ(report->camera_started.size(), 2u);
  }
  for (int c = 0; c < 2; ++c) {
    // Flying: most of the 40 frames (the finder's own path in the last frame can take the place
    // where the ball is now, its candidates' middles lying on the cells' 4 px grid; it stands
    // alone in this hall).
    EXPECT_GE(flying.camera_started[c], 36) << "camera " << c;
    // Held still alone for its last 8 frames: those count as well. (Without the hall's test:
    // flying 26 and 30, held 23 and 25.)
    EXPECT_GE(alone.camera_started[c], flying.camera_started[c]) << "camera " << c;
    EXPECT_GE(alone.camera_started[c], 38) << "camera " << c;
    // Before the shirt: at most its first two still frames more than the 32 flying ones.
    EXPECT_LE(before_shirt.camera_started[c], 34) << "camera " << c;
  }
  EXPECT_GE(alone.frames_startable, 38);
  EXPECT_LE(before_shirt.frames_startable, 34);
}

}  // namespace
}  // namespace p4
