// Where a club puts its cameras: high behind each end and at the sides of the table. Used by the
// simulator (and by tests) to build a rig of N cameras for an image size.
#pragma once

#include <cstdint>

#include "p4/geometry/rig.h"
#include "p4/sim/scene.h"
#include "p4/sim/trajectory.h"

namespace p4::sim {

// Cameras in this order: side (y < 0); high behind A, off to the y < 0 side; high behind B, off
// to the y > 0 side (so the player at that end does not hide the ball); other side; then the four
// corners. n in [1, 8]; focal length 0.78 * width (about 65 degrees across); optional
// moderate barrel distortion (k1 = -0.08, k2 = 0.02) as webcams have.
struct ClubRigOptions {
  double hfov_deg = 0.0;  // field of view across the picture; 0: focal length 0.78 * width
  double jitter_m = 0.0;  // each camera moved by up to this (and its aim by half of it)
  uint64_t seed = 0;      // of the jitter
};
Rig ClubRig(int n, int width, int height, bool distortion, const ClubRigOptions& options = {});

// The scene content at frame time t: `exposure` seconds centred on t, sampled every ~2 mm of
// ball travel (1 to 64 samples); players follow the ball across their end.
FrameContent ContentAt(const Trajectory& trajectory, double t, double exposure);

}  // namespace p4::sim
