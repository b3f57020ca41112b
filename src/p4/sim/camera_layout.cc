#include "p4/sim/camera_layout.h"

#include <algorithm>
#include <cmath>

#include "p4/geometry/look_at.h"

namespace p4::sim {

Rig ClubRig(int n, int width, int height, bool distortion) {
  struct Place {
    Eigen::Vector3d eye, target;
  };
  const Place places[] = {
      {{0.3, -3.6, 1.4}, {0.0, 0.0, 0.1}},  {{-4.0, -1.8, 2.3}, {0.3, 0.0, 0.0}},
      {{4.0, 1.8, 2.3}, {-0.3, 0.0, 0.0}},  {{-0.3, 3.6, 1.4}, {0.0, 0.0, 0.1}},
      {{-3.3, -2.8, 2.2}, {0.0, 0.0, 0.0}}, {{3.3, 2.8, 2.2}, {0.0, 0.0, 0.0}},
      {{3.3, -2.8, 2.2}, {0.0, 0.0, 0.0}},  {{-3.3, 2.8, 2.2}, {0.0, 0.0, 0.0}},
  };
  Rig rig;
  for (int i = 0; i < std::clamp(n, 1, 8); ++i) {
    Camera camera;
    camera.name = "cam" + std::to_string(i);
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = 0.78 * width;
    camera.cx = (width - 1) / 2.0 + 3.5;
    camera.cy = (height - 1) / 2.0 - 2.5;
    if (distortion) camera.distortion = {-0.08, 0.02, 0.0, 0.0, 0.0};
    camera.cam_from_world = LookAt(places[i].eye, places[i].target);
    rig.cameras.push_back(camera);
  }
  return rig;
}

FrameContent ContentAt(const Trajectory& trajectory, double t, double exposure) {
  FrameContent content;
  const auto centre = trajectory.At(t);
  double ball_y = 0.3 * std::sin(0.8 * t);
  if (centre) {
    ball_y = centre->position.y();
    const double travel = centre->velocity.norm() * exposure;
    const int samples = std::clamp(static_cast<int>(std::ceil(travel / 0.002)), 1, 64);
    for (int k = 0; k < samples; ++k) {
      const double tk = t + exposure * ((k + 0.5) / samples - 0.5);
      const auto s = trajectory.At(tk);
      if (s) content.ball.push_back(s->position);
    }
  }
  const double follow = std::clamp(0.7 * ball_y, -0.9, 0.9);
  content.players[0] = {-2.25 - 0.1 * std::sin(0.9 * t), follow - 0.25};
  content.players[1] = {2.25 + 0.1 * std::sin(1.1 * t + 1.0), follow + 0.25};
  return content;
}

}  // namespace p4::sim
