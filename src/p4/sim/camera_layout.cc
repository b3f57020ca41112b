#include "p4/sim/camera_layout.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "p4/geometry/look_at.h"

namespace p4::sim {

Rig ClubRig(int n, int width, int height, bool distortion, const ClubRigOptions& options) {
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
  std::mt19937_64 rng(options.seed * 31 + 7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto jitter = [&](double size) {
    Eigen::Vector3d offset;
    for (int k = 0; k < 3; ++k) offset[k] = size * unit(rng);  // in order: x, y, z
    return offset;
  };
  for (int i = 0; i < std::clamp(n, 1, 8); ++i) {
    Camera camera;
    camera.name = "cam" + std::to_string(i);
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = options.hfov_deg > 0.0
                                ? width / (2.0 * std::tan(options.hfov_deg * M_PI / 360.0))
                                : 0.78 * width;
    camera.cx = (width - 1) / 2.0 + 3.5;
    camera.cy = (height - 1) / 2.0 - 2.5;
    if (distortion) camera.distortion = {-0.08, 0.02, 0.0, 0.0, 0.0};
    const Eigen::Vector3d eye = places[i].eye + jitter(options.jitter_m);
    const Eigen::Vector3d target = places[i].target + jitter(0.5 * options.jitter_m);
    camera.cam_from_world = LookAt(eye, target);
    rig.cameras.push_back(camera);
  }
  return rig;
}

FrameContent ContentAt(const Trajectory& trajectory, double t, double exposure) {
  FrameContent content;
  content.t = t;
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
