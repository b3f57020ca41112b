#include "p4/sim/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "p4/core/table.h"

namespace p4::sim {
namespace {

struct Rgb {
  float r, g, b;
};

// BT.601 limited range.
inline void ToYuv(const Rgb& c, float* y, float* u, float* v) {
  const float luma = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
  *y = 16.0f + 219.0f * luma;
  *u = 128.0f + 224.0f * (c.b - luma) / 1.772f;
  *v = 128.0f + 224.0f * (c.r - luma) / 1.402f;
}

inline uint8_t Clamp8(float x) { return static_cast<uint8_t>(std::clamp(x + 0.5f, 0.0f, 255.0f)); }

const Eigen::Vector3d kLight = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();

inline Rgb Shade(const Rgb& albedo, const Eigen::Vector3d& normal, double ambient = 0.55) {
  const float k = static_cast<float>(ambient + (1.0 - ambient) * std::max(0.0, normal.dot(kLight)));
  return {albedo.r * k, albedo.g * k, albedo.b * k};
}

struct Box {
  Eigen::Vector3d lo, hi;
  Rgb color;
  int kind;  // 0 plain, 1 table top (lines, markers)
};

// Slab test; returns entry distance and the normal of the entry face.
bool HitBox(const Box& box, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double* t_hit,
            Eigen::Vector3d* normal) {
  double t0 = 1e-6, t1 = 1e30;
  int axis = -1;
  double sign = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (o[a] < box.lo[a] || o[a] > box.hi[a]) return false;
      continue;
    }
    double ta = (box.lo[a] - o[a]) / d[a];
    double tb = (box.hi[a] - o[a]) / d[a];
    double s = -1.0;
    if (ta > tb) {
      std::swap(ta, tb);
      s = 1.0;
    }
    if (ta > t0) {
      t0 = ta;
      axis = a;
      sign = s;
    }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis < 0) return false;  // inside the box
  *t_hit = t0;
  *normal = Eigen::Vector3d::Zero();
  (*normal)[axis] = sign;
  return true;
}

std::vector<Box> StaticBoxes() {
  using table::kHalfLength;
  using table::kHalfWidth;
  std::vector<Box> boxes;
  boxes.push_back({{-kHalfLength, -kHalfWidth, -0.025},
                   {kHalfLength, kHalfWidth, 0.0},
                   {0.05f, 0.17f, 0.36f},
                   1});
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const Eigen::Vector3d c(sx * 1.05, sy * 0.6, 0.0);
      boxes.push_back({c + Eigen::Vector3d(-0.03, -0.03, table::kFloorZ),
                       c + Eigen::Vector3d(0.03, 0.03, -0.025),
                       {0.12f, 0.12f, 0.13f},
                       0});
    }
  }
  for (double sy : {-1.0, 1.0}) {  // net posts
    const double y0 = sy * table::kNetHalfLength, y1 = sy * (table::kNetHalfLength + 0.02);
    boxes.push_back({{-0.012, std::min(y0, y1), -0.03},
                     {0.012, std::max(y0, y1), table::kNetHeight},
                     {0.08f, 0.08f, 0.1f},
                     0});
  }
  boxes.push_back({{-0.002, -table::kNetHalfLength, table::kNetHeight - 0.015},
                   {0.002, table::kNetHalfLength, table::kNetHeight},
                   {0.92f, 0.92f, 0.92f},
                   0});
  return boxes;
}

constexpr double kRoomX = 7.0, kRoomY = 5.0, kCeiling = 3.2;

Rgb RoomColor(const Eigen::Vector3d& p, int face) {
  if (face == 0) {  // floor: red-brown sports floor with faint boards
    const float stripe = (static_cast<int>(std::floor(p.y() / 0.5)) % 2 == 0) ? 1.0f : 0.94f;
    return {0.40f * stripe, 0.17f * stripe, 0.13f * stripe};
  }
  if (face == 1) return {0.85f, 0.85f, 0.86f};                     // ceiling
  if (p.z() < table::kFloorZ + 0.75) return {0.08f, 0.1f, 0.28f};  // barrier band
  return {0.72f, 0.70f, 0.64f};
}

struct Ellipsoid {
  Eigen::Vector3d c, r;
  Rgb color;
};

std::vector<Ellipsoid> PlayerBody(const Eigen::Vector2d& feet, bool player_b, bool orange_shirt) {
  const double f = table::kFloorZ;
  const double toward = player_b ? -1.0 : 1.0;  // faces the table
  const Rgb shirt = player_b ? (orange_shirt ? Rgb{0.95f, 0.45f, 0.12f} : Rgb{0.13f, 0.13f, 0.14f})
                             : Rgb{0.12f, 0.16f, 0.42f};
  const Rgb skin{0.82f, 0.6f, 0.5f};
  const Rgb shorts{0.08f, 0.08f, 0.1f};
  const double x = feet.x(), y = feet.y();
  return {
      {{x, y - 0.11, f + 0.45}, {0.08, 0.08, 0.45}, skin},
      {{x, y + 0.11, f + 0.45}, {0.08, 0.08, 0.45}, skin},
      {{x, y, f + 0.85}, {0.14, 0.2, 0.14}, shorts},
      {{x, y, f + 1.2}, {0.13, 0.22, 0.3}, shirt},
      {{x, y, f + 1.63}, {0.1, 0.09, 0.12}, skin},
      {{x + toward * 0.22, y + 0.3, f + 1.1}, {0.26, 0.05, 0.05}, skin},
  };
}

// Ray-ellipsoid (axis-aligned) nearest positive hit; d need not be unit.
bool HitEllipsoid(const Ellipsoid& e, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                  double* t_hit) {
  const Eigen::Vector3d oc = (o - e.c).cwiseQuotient(e.r);
  const Eigen::Vector3d dd = d.cwiseQuotient(e.r);
  const double a = dd.squaredNorm(), b = oc.dot(dd), c = oc.squaredNorm() - 1.0;
  const double disc = b * b - a * c;
  if (disc < 0.0) return false;
  const double t = (-b - std::sqrt(disc)) / a;
  if (t <= 1e-6) return false;
  *t_hit = t;
  return true;
}

}  // namespace

bool RenderOptions::IsValid(std::string* error) const {
  if (!(noise_sigma_luma >= 0.0 && noise_sigma_chroma >= 0.0)) {
    if (error) *error = "noise must be >= 0";
    return false;
  }
  if (static_supersampling < 1 || static_supersampling > 8 || ball_min_samples < 1) {
    if (error) *error = "supersampling must be in [1, 8] and ball samples >= 1";
    return false;
  }
  return true;
}

CameraRenderer::CameraRenderer(const Camera& camera, const SceneOptions& scene,
                               const RenderOptions& options)
    : camera_(camera), scene_(scene), options_(options), w_(camera.width), h_(camera.height) {
  if (camera_.HasDistortion()) {
    undistorted_.resize(static_cast<std::size_t>(w_) * h_ * 2);
    for (int v = 0; v < h_; ++v) {
      for (int u = 0; u < w_; ++u) {
        const Eigen::Vector2d n = camera_.NormalizedFromPixel({u, v});
        undistorted_[(static_cast<std::size_t>(v) * w_ + u) * 2] = static_cast<float>(n.x());
        undistorted_[(static_cast<std::size_t>(v) * w_ + u) * 2 + 1] = static_cast<float>(n.y());
      }
    }
  }
  RenderStatic();
  // Noise tables: twice a frame's size, read at a random offset each frame.
  std::mt19937_64 rng(options_.seed * 7919 + 17);
  const std::size_t luma = static_cast<std::size_t>(w_) * h_;
  noise_luma_.resize(2 * luma);
  noise_chroma_.resize(luma);
  std::normal_distribution<double> n_luma(0.0, options_.noise_sigma_luma);
  std::normal_distribution<double> n_chroma(0.0, options_.noise_sigma_chroma);
  for (auto& x : noise_luma_)
    x = static_cast<int8_t>(std::clamp(std::lround(n_luma(rng)), -127L, 127L));
  for (auto& x : noise_chroma_)
    x = static_cast<int8_t>(std::clamp(std::lround(n_chroma(rng)), -127L, 127L));
}

Eigen::Vector2d CameraRenderer::Normalized(double u, double v) const {
  if (undistorted_.empty()) return {(u - camera_.cx) / camera_.fx, (v - camera_.cy) / camera_.fy};
  // Bilinear interpolation of the per-pixel table (clamped at the border).
  const double uc = std::clamp(u, 0.0, w_ - 1.0001), vc = std::clamp(v, 0.0, h_ - 1.0001);
  const int u0 = static_cast<int>(uc), v0 = static_cast<int>(vc);
  const double fu = uc - u0 + (u - uc), fv = vc - v0 + (v - vc);  // extrapolates at the border
  const auto at = [&](int uu, int vv, int k) {
    return static_cast<double>(undistorted_[(static_cast<std::size_t>(vv) * w_ + uu) * 2 + k]);
  };
  Eigen::Vector2d n;
  for (int k = 0; k < 2; ++k) {
    const double a = at(u0, v0, k) + fu * (at(u0 + 1, v0, k) - at(u0, v0, k));
    const double b = at(u0, v0 + 1, k) + fu * (at(u0 + 1, v0 + 1, k) - at(u0, v0 + 1, k));
    n[k] = a + fv * (b - a);
  }
  return n;
}

void CameraRenderer::RenderStatic() {
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  static_yuv_.assign(3 * n, 0.0f);
  static_depth_.assign(n, 1e9f);
  const std::vector<Box> boxes = StaticBoxes();
  const Eigen::Matrix3d world_from_cam = camera_.cam_from_world.rotation.transpose();
  const Eigen::Vector3d origin = camera_.Center();
  const int ss = options_.static_supersampling;

  // Traces one ray (direction d = world_from_cam * (x, y, 1), so t is the camera z depth).
  const auto trace = [&](const Eigen::Vector3d& d, double* depth) -> Rgb {
    double best = 1e30;
    Rgb color{0, 0, 0};
    // Room (from inside): the nearest face the ray leaves through.
    int face = -1;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(d[a]) < 1e-15) continue;
      double bound;
      if (a == 0)
        bound = d[a] > 0 ? kRoomX : -kRoomX;
      else if (a == 1)
        bound = d[a] > 0 ? kRoomY : -kRoomY;
      else
        bound = d[a] > 0 ? kCeiling : table::kFloorZ;
      const double t = (bound - origin[a]) / d[a];
      if (t > 0 && t < best) {
        best = t;
        face = a == 2 ? (d[a] > 0 ? 1 : 0) : 2;
      }
    }
    Eigen::Vector3d normal =
        face == 0 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(-d.normalized());
    if (face >= 0) color = Shade(RoomColor(origin + best * d, face), normal, 0.7);
    for (const Box& box : boxes) {
      double t;
      Eigen::Vector3d nb;
      if (HitBox(box, origin, d, &t, &nb) && t < best) {
        best = t;
        Rgb albedo = box.color;
        const Eigen::Vector3d p = origin + t * d;
        if (box.kind == 1 && nb.z() > 0.5) {
          const bool edge = std::abs(p.x()) > table::kHalfLength - table::kEdgeLineWidth ||
                            std::abs(p.y()) > table::kHalfWidth - table::kEdgeLineWidth;
          const bool centre = std::abs(p.y()) < table::kCentreLineWidth / 2.0;
          if (edge || centre) albedo = {0.93f, 0.93f, 0.93f};
          for (const MarkerQuad& m : scene_.markers) {
            const Eigen::Vector3d ex = m.corners[1] - m.corners[0];
            const Eigen::Vector3d ey = m.corners[3] - m.corners[0];
            const double a = (p - m.corners[0]).dot(ex) / ex.squaredNorm();
            const double b = (p - m.corners[0]).dot(ey) / ey.squaredNorm();
            // A white quiet zone of one module around the marker.
            const double q = 1.0 / m.cells;
            if (a < -q || a > 1 + q || b < -q || b > 1 + q) continue;
            albedo = {0.95f, 0.95f, 0.95f};
            if (a >= 0 && a < 1 && b >= 0 && b < 1) {
              const int c = static_cast<int>(a * m.cells), r = static_cast<int>(b * m.cells);
              if (m.black[r * m.cells + c]) albedo = {0.04f, 0.04f, 0.04f};
            }
          }
        }
        color = Shade(albedo, nb);
      }
    }
    // The net's mesh: a see-through dark layer in the plane x = 0.
    if (std::abs(d.x()) > 1e-12) {
      const double t = -origin.x() / d.x();
      if (t > 0 && t < best) {
        const Eigen::Vector3d p = origin + t * d;
        if (std::abs(p.y()) < table::kNetHalfLength && p.z() > 0.0 &&
            p.z() < table::kNetHeight - 0.015) {
          constexpr float kAlpha = 0.45f;
          color = {color.r * (1 - kAlpha) + 0.05f * kAlpha, color.g * (1 - kAlpha) + 0.06f * kAlpha,
                   color.b * (1 - kAlpha) + 0.1f * kAlpha};
        }
      }
    }
    *depth = best;
    return color;
  };

  for (int v = 0; v < h_; ++v) {
    for (int u = 0; u < w_; ++u) {
      Rgb sum{0, 0, 0};
      for (int sy = 0; sy < ss; ++sy) {
        for (int sx = 0; sx < ss; ++sx) {
          const Eigen::Vector2d nrm =
              Normalized(u + (sx + 0.5) / ss - 0.5, v + (sy + 0.5) / ss - 0.5);
          double depth;
          const Rgb c = trace(world_from_cam * Eigen::Vector3d(nrm.x(), nrm.y(), 1.0), &depth);
          sum.r += c.r, sum.g += c.g, sum.b += c.b;
        }
      }
      const float k = 1.0f / (ss * ss);
      const Rgb mean{sum.r * k, sum.g * k, sum.b * k};
      const std::size_t i = static_cast<std::size_t>(v) * w_ + u;
      ToYuv(mean, &static_yuv_[i], &static_yuv_[n + i], &static_yuv_[2 * n + i]);
      double depth;
      const Eigen::Vector2d centre = Normalized(u, v);
      trace(world_from_cam * Eigen::Vector3d(centre.x(), centre.y(), 1.0), &depth);
      static_depth_[i] = static_cast<float>(depth);
    }
  }
  work_yuv_ = static_yuv_;
  work_depth_ = static_depth_;
  static_i420_ = I420Image(w_, h_);
  WriteRect({0, 0, w_, h_}, &static_i420_);
}

CameraRenderer::Rect CameraRenderer::ClipEven(double x0, double y0, double x1, double y1) const {
  Rect r;
  r.x0 = std::max(0, static_cast<int>(std::floor(x0)) & ~1);
  r.y0 = std::max(0, static_cast<int>(std::floor(y0)) & ~1);
  r.x1 = std::min(w_, (static_cast<int>(std::ceil(x1)) + 2) & ~1);
  r.y1 = std::min(h_, (static_cast<int>(std::ceil(y1)) + 2) & ~1);
  return r;
}

void CameraRenderer::RestoreWork(const Rect& r) {
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  for (int v = r.y0; v < r.y1; ++v) {
    const std::size_t i = static_cast<std::size_t>(v) * w_ + r.x0;
    const std::size_t len = static_cast<std::size_t>(r.x1 - r.x0) * sizeof(float);
    for (int p = 0; p < 3; ++p) std::memcpy(&work_yuv_[p * n + i], &static_yuv_[p * n + i], len);
    std::memcpy(&work_depth_[i], &static_depth_[i], len);
  }
}

void CameraRenderer::WriteRect(const Rect& r, I420Image* out) const {
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  for (int v = r.y0; v < r.y1; ++v) {
    for (int u = r.x0; u < r.x1; ++u)
      out->y()[v * w_ + u] = Clamp8(work_yuv_[static_cast<std::size_t>(v) * w_ + u]);
  }
  const int cw = w_ / 2;
  for (int v = r.y0 / 2; v < r.y1 / 2; ++v) {
    for (int u = r.x0 / 2; u < r.x1 / 2; ++u) {
      for (int p = 1; p <= 2; ++p) {
        const float* plane = &work_yuv_[p * n];
        const std::size_t i =
            static_cast<std::size_t>(2 * v) * w_ + static_cast<std::size_t>(2 * u);
        const float mean = 0.25f * (plane[i] + plane[i + 1] + plane[i + w_] + plane[i + w_ + 1]);
        (p == 1 ? out->u() : out->v())[v * cw + u] = Clamp8(mean);
      }
    }
  }
}

CameraRenderer::Rect CameraRenderer::RenderPlayers(const FrameContent& content) {
  if (!scene_.players) return {};
  Rect all{w_, h_, 0, 0};
  const Eigen::Matrix3d world_from_cam = camera_.cam_from_world.rotation.transpose();
  const Eigen::Vector3d origin = camera_.Center();
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  for (int k = 0; k < 2; ++k) {
    // Each ellipsoid is z-buffered on its own projected box: far fewer ray tests than one box
    // around the whole body.
    for (const Ellipsoid& e : PlayerBody(content.players[k], k == 1, scene_.orange_shirt)) {
      double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
      bool behind = false;
      for (int c = 0; c < 8 && !behind; ++c) {
        const Eigen::Vector3d p =
            e.c + Eigen::Vector3d((c & 1) ? e.r.x() : -e.r.x(), (c & 2) ? e.r.y() : -e.r.y(),
                                  (c & 4) ? e.r.z() : -e.r.z());
        const auto px = camera_.Project(p);
        if (!px) {
          behind = true;
          break;
        }
        x0 = std::min(x0, px->x()), y0 = std::min(y0, px->y());
        x1 = std::max(x1, px->x()), y1 = std::max(y1, px->y());
      }
      if (behind || x1 < 0 || y1 < 0 || x0 >= w_ || y0 >= h_) continue;
      const Rect r = ClipEven(x0 - 2, y0 - 2, x1 + 2, y1 + 2);
      if (r.empty()) continue;
      for (int v = r.y0; v < r.y1; ++v) {
        for (int u = r.x0; u < r.x1; ++u) {
          const std::size_t i = static_cast<std::size_t>(v) * w_ + u;
          const Eigen::Vector2d nrm = Normalized(u, v);
          const Eigen::Vector3d d = world_from_cam * Eigen::Vector3d(nrm.x(), nrm.y(), 1.0);
          double t;
          if (!HitEllipsoid(e, origin, d, &t) || t >= work_depth_[i]) continue;
          const Eigen::Vector3d p = origin + t * d;
          const Eigen::Vector3d normal =
              (p - e.c).cwiseQuotient(e.r.cwiseProduct(e.r)).normalized();
          ToYuv(Shade(e.color, normal, 0.5), &work_yuv_[i], &work_yuv_[n + i],
                &work_yuv_[2 * n + i]);
          work_depth_[i] = static_cast<float>(t);
        }
      }
      all.x0 = std::min(all.x0, r.x0), all.y0 = std::min(all.y0, r.y0);
      all.x1 = std::max(all.x1, r.x1), all.y1 = std::max(all.y1, r.y1);
      dirty_.push_back(r);
    }
  }
  return all;
}

CameraRenderer::Rect CameraRenderer::RenderBall(const FrameContent& content, double* visible) {
  *visible = 0.0;
  if (content.ball.empty()) return {};
  const double radius = table::kBallRadius;
  std::vector<Eigen::Vector3d> centres;  // camera frame
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const Eigen::Vector3d& p : content.ball) {
    const Eigen::Vector3d c = camera_.cam_from_world * p;
    if (c.z() < 0.1) return {};  // the ball at the lens: not drawn
    centres.push_back(c);
    const auto px = camera_.Project(p);
    if (!px) return {};
    const double r_px = 1.3 * std::max(camera_.fx, camera_.fy) * radius / c.z() + 2.0;
    x0 = std::min(x0, px->x() - r_px), y0 = std::min(y0, px->y() - r_px);
    x1 = std::max(x1, px->x() + r_px), y1 = std::max(y1, px->y() + r_px);
  }
  if (x1 < 0 || y1 < 0 || x0 >= w_ || y0 >= h_) return {};
  const Rect r = ClipEven(x0, y0, x1, y1);
  if (r.empty()) return {};
  const Rgb albedo = scene_.orange_ball ? Rgb{1.0f, 0.42f, 0.05f} : Rgb{0.95f, 0.95f, 0.92f};
  const Eigen::Vector3d light = camera_.cam_from_world.rotation * kLight;
  const int samples_t = static_cast<int>(centres.size());
  const int samples = std::max(options_.ball_min_samples, samples_t);
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  int64_t sphere_hits = 0, shown_hits = 0;
  for (int v = r.y0; v < r.y1; ++v) {
    for (int u = r.x0; u < r.x1; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w_ + u;
      const float depth = work_depth_[i];
      float sy = 0, su = 0, sv = 0;
      int hits = 0;
      for (int s = 0; s < samples; ++s) {
        const int cell =
            (s * 11) % 16;  // a 4x4 stratified subpixel pattern, decorrelated from time
        const double du = ((cell % 4) + 0.5) / 4.0 - 0.5,
                     dv = ((cell >> 2) + 0.5) / 4.0 - 0.5;  // row of the grid
        const Eigen::Vector2d nrm = Normalized(u + du, v + dv);
        const Eigen::Vector3d d(nrm.x(), nrm.y(), 1.0);
        const Eigen::Vector3d& c = centres[s % samples_t];
        const double dc = d.dot(c), dd = d.squaredNorm();
        const double disc = dc * dc - dd * (c.squaredNorm() - radius * radius);
        if (disc < 0.0) continue;
        const double t = (dc - std::sqrt(disc)) / dd;
        if (t <= 0.0) continue;
        ++sphere_hits;
        if (t >= depth) continue;
        ++shown_hits;
        const Eigen::Vector3d normal = (t * d - c) / radius;
        const Eigen::Vector3d view = -(t * d).normalized();
        const Eigen::Vector3d reflect = 2.0 * normal.dot(light) * normal - light;
        // Halls light a matte ball from many lamps: mostly ambient, a little sun, a soft highlight.
        Rgb col = Shade(albedo, normal, 0.8);
        const float spec =
            0.08f * static_cast<float>(std::pow(std::max(0.0, reflect.dot(view)), 30.0));
        col = {col.r + spec, col.g + spec, col.b + spec};
        float yy, uu, vv;
        ToYuv(col, &yy, &uu, &vv);
        sy += yy, su += uu, sv += vv;
        ++hits;
      }
      if (hits == 0) continue;
      const float k = 1.0f / samples, miss = static_cast<float>(samples - hits) * k;
      work_yuv_[i] = sy * k + miss * work_yuv_[i];
      work_yuv_[n + i] = su * k + miss * work_yuv_[n + i];
      work_yuv_[2 * n + i] = sv * k + miss * work_yuv_[2 * n + i];
    }
  }
  dirty_.push_back(r);
  const auto centre = camera_.Project(content.ball[content.ball.size() / 2]);
  if (sphere_hits > 0 && centre && camera_.InImage(*centre)) {
    *visible = static_cast<double>(shown_hits) / static_cast<double>(sphere_hits);
  }
  return r;
}

void CameraRenderer::AddNoise(uint64_t frame_index, I420Image* out) const {
  std::mt19937_64 rng(options_.seed * 1000003 + frame_index * 7 + 1);
  const std::size_t luma = static_cast<std::size_t>(w_) * h_;
  const std::size_t chroma = luma / 4;
  const std::size_t offset_y = rng() % (noise_luma_.size() - luma);
  const std::size_t offset_u = rng() % (noise_chroma_.size() - 2 * chroma);
  const std::size_t offset_v = rng() % (noise_chroma_.size() - 2 * chroma);
  const auto add = [](uint8_t* dst, const int8_t* noise, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) {
      const int x = dst[i] + noise[i];
      dst[i] = static_cast<uint8_t>(x < 0 ? 0 : (x > 255 ? 255 : x));
    }
  };
  add(out->y(), noise_luma_.data() + offset_y, luma);
  add(out->u(), noise_chroma_.data() + offset_u, chroma);
  add(out->v(), noise_chroma_.data() + offset_v, chroma);
}

double CameraRenderer::Render(const FrameContent& content, uint64_t frame_index, I420Image* out) {
  if (out->width() != w_ || out->height() != h_) *out = I420Image(w_, h_);
  for (const Rect& r : dirty_) RestoreWork(r);
  dirty_.clear();
  RenderPlayers(content);
  double visible = 0.0;
  RenderBall(content, &visible);
  std::memcpy(out->bytes().data(), static_i420_.bytes().data(), out->bytes().size());
  for (const Rect& r : dirty_) WriteRect(r, out);
  AddNoise(frame_index, out);
  return visible;
}

}  // namespace p4::sim
