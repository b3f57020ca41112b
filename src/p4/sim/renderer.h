// Renders one camera's view of the simulated scene into I420 frames (BT.601, limited range),
// the way a real camera would deliver them: a supersampled static background (rendered once),
// players, the ball shaded and anti-aliased with motion blur from sub-frame samples over the
// exposure, sensor noise, and the camera's own lens: distortion, defocus and vignetting. Colours
// and light come from the scene's Look (auto-exposure drift included).
//
// Frame time convention: a frame stamped t is exposed over [t - exposure/2, t + exposure/2], so
// the blurred ball's centroid sits at the projection of the ball at t.
//
// Thread safety: one renderer per camera and per thread; Render() is deterministic for a given
// frame index whatever the order of calls.
#pragma once

#include <cstdint>
#include <vector>

#include "p4/core/image.h"
#include "p4/geometry/camera.h"
#include "p4/sim/scene.h"

namespace p4::sim {

struct RenderOptions {
  double noise_sigma_luma = 2.0;  // sensor noise, 8-bit levels
  double noise_sigma_chroma = 1.5;
  int static_supersampling = 3;  // per axis, for the background (3 => 9 rays a pixel)
  int ball_min_samples = 16;     // rays per pixel for the ball (AA and blur share them)
  double vignetting = 0.0;       // brightness lost at the picture's corners, share
  double defocus_px = 0.0;       // lens blur: Gaussian sigma in pixels (0: sharp)
  uint64_t seed = 1;

  bool IsValid(std::string* error) const;
};

class CameraRenderer {
 public:
  // Renders the static background at once (the expensive part; ~1 s at 1280x720).
  CameraRenderer(const Camera& camera, const SceneOptions& scene, const RenderOptions& options);

  // Renders one frame. Returns how much of the ball this camera sees: the share of the ball's
  // image (inside the picture) not hidden by players or the scene, in [0, 1]; 0 without a ball.
  double Render(const FrameContent& content, uint64_t frame_index, I420Image* out);

  const Camera& camera() const { return camera_; }

 private:
  struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1), even-aligned
    bool empty() const { return x1 <= x0 || y1 <= y0; }
  };

  Eigen::Vector2d Normalized(double u, double v) const;  // pixel -> undistorted normalized
  void RenderStatic();
  void RestoreWork(const Rect& r);
  void WriteRect(const Rect& r, I420Image* out) const;
  Rect ClipEven(double x0, double y0, double x1, double y1) const;
  Rect RenderPlayers(const FrameContent& content);
  Rect RenderBall(const FrameContent& content, double* visible);
  void AddNoise(uint64_t frame_index, I420Image* out) const;

  Camera camera_;
  SceneOptions scene_;
  RenderOptions options_;
  int w_ = 0, h_ = 0;
  std::vector<float> undistorted_;                // 2 floats a pixel when the camera has distortion
  std::vector<float> static_yuv_, static_depth_;  // full-resolution Y, U, V planes; z depth
  std::vector<float> work_yuv_, work_depth_;
  I420Image static_i420_;
  std::vector<int8_t> noise_luma_, noise_chroma_;
  std::vector<float> kernel_;  // defocus kernel (empty when sharp)
  std::vector<Rect> dirty_;
};

}  // namespace p4::sim
