#include "p4/sim/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include "p4/core/table.h"

namespace p4::sim {
namespace {

// BT.601 limited range, as the camera encodes `c` after its white balance and exposure gain: the
// sensor clips at 1 (lamps, highlights).
inline void ToYuv(const Rgb& in, const Look& look, float* y, float* u, float* v) {
  const auto clip = [&](float x, float wb) {
    return std::clamp(x * wb * static_cast<float>(look.gain), 0.0f, 1.0f);
  };
  const Rgb c{clip(in.r, look.white_balance.r), clip(in.g, look.white_balance.g),
              clip(in.b, look.white_balance.b)};
  const float luma = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
  *y = 16.0f + 219.0f * luma;
  *u = 128.0f + 224.0f * (c.b - luma) / 1.772f;
  *v = 128.0f + 224.0f * (c.r - luma) / 1.402f;
}

inline uint8_t Clamp8(float x) { return static_cast<uint8_t>(std::clamp(x + 0.5f, 0.0f, 255.0f)); }

// Lambert shading: `ambient` of the light from all round, the rest from `light` (unit).
inline Rgb Shade(const Rgb& albedo, const Eigen::Vector3d& normal, const Eigen::Vector3d& light,
                 double ambient) {
  const float k = static_cast<float>(ambient + (1.0 - ambient) * std::max(0.0, normal.dot(light)));
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

std::vector<Box> StaticBoxes(const Look& look) {
  using table::kHalfLength;
  using table::kHalfWidth;
  std::vector<Box> boxes;
  boxes.push_back(
      {{-kHalfLength, -kHalfWidth, -0.025}, {kHalfLength, kHalfWidth, 0.0}, look.table, 1});
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

// Block letters 12 cm wide with 4 cm strokes along a band: `a` along the band, `h` in [0, 1]
// across it. Some letters are left out, as between words.
bool Lettering(double a, double h) {
  const double cell = std::floor(a / 0.12);
  const double x = a - 0.12 * cell;
  if (h < 0.0 || h > 1.0 || x > 0.09) return false;
  const auto word = static_cast<uint32_t>(static_cast<int64_t>(cell) * 2654435761u) >> 28;
  if (word % 5 == 0) return false;
  const bool stem = x < 0.035 || (word % 2 == 0 && x > 0.055);
  const bool bar = h < 0.25 || h > 0.75 || (word % 3 == 0 && std::abs(h - 0.5) < 0.12);
  return stem || bar;
}

// A wall point as (wall index as Banner::wall, along, height above the table top).
void WallCoordinates(const Eigen::Vector3d& p, int* wall, double* along) {
  if (std::abs(std::abs(p.x()) - kRoomX) < 1e-6) {
    *wall = p.x() < 0 ? 0 : 1;
    *along = p.y();
  } else {
    *wall = p.y() < 0 ? 2 : 3;
    *along = p.x();
  }
}

// The room's surfaces: floor (face 0), ceiling (1) and walls (2) with their banners, lettering,
// lamps and windows; *emits is set for light sources (not shaded).
Rgb RoomColor(const Look& look, const Eigen::Vector3d& p, int face, bool* emits) {
  *emits = false;
  if (face == 0) {  // floor with faint boards
    const float stripe = (static_cast<int>(std::floor(p.y() / 0.5)) % 2 == 0) ? 1.0f : 0.94f;
    return {look.floor.r * stripe, look.floor.g * stripe, look.floor.b * stripe};
  }
  if (face == 1) {
    for (const Lamp& l : look.lamps) {
      if (l.ceiling && std::abs(p.x() - l.centre.x()) < l.size.x() / 2 &&
          std::abs(p.y() - l.centre.y()) < l.size.y() / 2) {
        *emits = true;
        return {l.brightness, l.brightness, l.brightness};
      }
    }
    return look.ceiling;
  }
  int wall = 0;
  double along = 0.0;
  WallCoordinates(p, &wall, &along);
  for (const Lamp& l : look.lamps) {
    if (!l.ceiling && l.wall == wall && std::abs(along - l.centre.x()) < l.size.x() / 2 &&
        std::abs(p.z() - l.centre.y()) < l.size.y() / 2) {
      *emits = true;
      return {l.brightness, l.brightness, l.brightness * 0.97f};
    }
  }
  for (const Banner& b : look.banners) {
    if (b.wall != wall || std::abs(along - b.along) > b.width / 2 ||
        std::abs(p.z() - b.z) > b.height / 2) {
      continue;
    }
    const double h = (p.z() - (b.z - b.height * 0.3)) / (b.height * 0.6);
    return Lettering(along - b.along + b.width / 2, h) ? b.lettering : b.color;
  }
  const double barrier_top = table::kFloorZ + 0.75;
  if (p.z() < barrier_top) {
    const double h = (p.z() - (table::kFloorZ + 0.2)) / 0.35;
    return Lettering(along + 10.0, h) ? look.barrier_lettering : look.barrier;
  }
  return look.wall;
}

struct Ellipsoid {
  Eigen::Vector3d c, r;
  Rgb color;
};

// A player: legs, shorts, shirt, head, a swinging arm and shoes, in the look's colours.
std::vector<Ellipsoid> PlayerBody(const Eigen::Vector2d& feet, bool player_b, const Look& look,
                                  double t) {
  const double f = table::kFloorZ;
  const double toward = player_b ? -1.0 : 1.0;  // faces the table
  const Rgb& shirt = player_b ? look.shirt_b : look.shirt_a;
  const double x = feet.x(), y = feet.y();
  // The arm swings about 1.5 times a second (a few metres a second at the hand).
  const double swing = look.arm_swing * std::sin(2.0 * M_PI * 1.5 * t + (player_b ? 2.0 : 0.0));
  return {
      {{x, y - 0.11, f + 0.45}, {0.08, 0.08, 0.45}, look.skin},
      {{x, y + 0.11, f + 0.45}, {0.08, 0.08, 0.45}, look.skin},
      {{x, y, f + 0.85}, {0.14, 0.2, 0.14}, look.shorts},
      {{x, y, f + 1.2}, {0.13, 0.22, 0.3}, shirt},
      {{x, y, f + 1.63}, {0.1, 0.09, 0.12}, look.skin},
      {{x + toward * 0.22, y + 0.3 + swing, f + 1.1 + 0.4 * std::abs(swing)},
       {0.26, 0.05, 0.05},
       look.skin},
      {{x + toward * 0.05, y - 0.11, f + 0.04}, {0.14, 0.05, 0.04}, look.shoes},
      {{x + toward * 0.05, y + 0.11, f + 0.04}, {0.14, 0.05, 0.04}, look.shoes},
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
  if (!(vignetting >= 0.0 && vignetting < 1.0) || !(defocus_px >= 0.0 && defocus_px <= 5.0)) {
    if (error) *error = "vignetting must be in [0, 1) and defocus in [0, 5] px";
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
  if (options_.defocus_px > 0.0) {
    const int m = static_cast<int>(std::ceil(3.0 * options_.defocus_px));
    float sum = 0.0f;
    for (int k = -m; k <= m; ++k) {
      kernel_.push_back(
          static_cast<float>(std::exp(-0.5 * k * k / (options_.defocus_px * options_.defocus_px))));
      sum += kernel_.back();
    }
    for (float& k : kernel_) k /= sum;
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
  const Look& look = scene_.look;
  const std::vector<Box> boxes = StaticBoxes(look);
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
    if (face >= 0) {
      bool emits = false;
      const Rgb room = RoomColor(look, origin + best * d, face, &emits);
      color = emits ? room : Shade(room, normal, look.light, std::min(1.0, look.ambient + 0.15));
    }
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
          if (edge || centre) albedo = look.lines;
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
        color = Shade(albedo, nb, look.light, look.ambient);
      }
    }
    // A spare ball lying still.
    if (look.spare_ball) {
      const double r = table::kBallRadius;
      const Ellipsoid spare{*look.spare_ball, {r, r, r}, look.ball};
      double t;
      if (HitEllipsoid(spare, origin, d, &t) && t < best) {
        best = t;
        const Eigen::Vector3d normal = (origin + t * d - spare.c) / r;
        color = Shade(look.ball, normal, look.light, look.ball_ambient);
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
      ToYuv(mean, look, &static_yuv_[i], &static_yuv_[n + i], &static_yuv_[2 * n + i]);
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
  // The lens: the work planes blurred by the defocus kernel (separable), then vignetted.
  const int rw = r.x1 - r.x0, rh = r.y1 - r.y0;
  const int m = static_cast<int>(kernel_.size()) / 2;
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  std::vector<float> planes(3 * static_cast<std::size_t>(rw) * rh);
  std::vector<float> rows;
  for (int p = 0; p < 3; ++p) {
    const float* src = &work_yuv_[p * n];
    float* dst = &planes[p * static_cast<std::size_t>(rw) * rh];
    if (m == 0) {
      for (int v = 0; v < rh; ++v) {
        std::memcpy(dst + static_cast<std::size_t>(v) * rw,
                    src + static_cast<std::size_t>(r.y0 + v) * w_ + r.x0, rw * sizeof(float));
      }
      continue;
    }
    const int ya = std::max(0, r.y0 - m), yb = std::min(h_, r.y1 + m);
    rows.assign(static_cast<std::size_t>(yb - ya) * rw, 0.0f);
    for (int v = ya; v < yb; ++v) {
      const float* row = src + static_cast<std::size_t>(v) * w_;
      for (int u = r.x0; u < r.x1; ++u) {
        float sum = 0.0f;
        for (int k = -m; k <= m; ++k) sum += kernel_[k + m] * row[std::clamp(u + k, 0, w_ - 1)];
        rows[static_cast<std::size_t>(v - ya) * rw + (u - r.x0)] = sum;
      }
    }
    for (int v = r.y0; v < r.y1; ++v) {
      for (int u = 0; u < rw; ++u) {
        float sum = 0.0f;
        for (int k = -m; k <= m; ++k) {
          sum += kernel_[k + m] *
                 rows[static_cast<std::size_t>(std::clamp(v + k, ya, yb - 1) - ya) * rw + u];
        }
        dst[static_cast<std::size_t>(v - r.y0) * rw + u] = sum;
      }
    }
  }
  // Vignetting: brightness falls with the squared distance from the centre, by `vignetting` at
  // the corners (applied to the levels above black and around grey).
  const double cx = (w_ - 1) / 2.0, cy = (h_ - 1) / 2.0, corner = cx * cx + cy * cy;
  const auto gain = [&](double u, double v) {
    return static_cast<float>(1.0 - options_.vignetting *
                                        ((u - cx) * (u - cx) + (v - cy) * (v - cy)) / corner);
  };
  for (int v = r.y0; v < r.y1; ++v) {
    for (int u = r.x0; u < r.x1; ++u) {
      const float y = planes[static_cast<std::size_t>(v - r.y0) * rw + (u - r.x0)];
      out->y()[v * w_ + u] = Clamp8(16.0f + gain(u, v) * (y - 16.0f));
    }
  }
  const int cw = w_ / 2;
  for (int v = r.y0 / 2; v < r.y1 / 2; ++v) {
    for (int u = r.x0 / 2; u < r.x1 / 2; ++u) {
      const float g = gain(2 * u + 0.5, 2 * v + 0.5);
      for (int p = 1; p <= 2; ++p) {
        const float* plane = &planes[p * static_cast<std::size_t>(rw) * rh];
        const std::size_t i = static_cast<std::size_t>(2 * v - r.y0) * rw + (2 * u - r.x0);
        const float mean = 0.25f * (plane[i] + plane[i + 1] + plane[i + rw] + plane[i + rw + 1]);
        (p == 1 ? out->u() : out->v())[v * cw + u] = Clamp8(128.0f + g * (mean - 128.0f));
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
    for (const Ellipsoid& e : PlayerBody(content.players[k], k == 1, scene_.look, content.t)) {
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
          ToYuv(Shade(e.color, normal, scene_.look.light, 0.5), scene_.look, &work_yuv_[i],
                &work_yuv_[n + i], &work_yuv_[2 * n + i]);
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
  // Each sample's centre in the image and a radius beyond which its rays all miss it.
  std::vector<Eigen::Vector3d> reach;  // x, y, radius^2 (px)
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const Eigen::Vector3d& p : content.ball) {
    const Eigen::Vector3d c = camera_.cam_from_world * p;
    if (c.z() < 0.1) return {};  // the ball at the lens: not drawn
    centres.push_back(c);
    const auto px = camera_.Project(p);
    if (!px) return {};
    const double r_px = 1.3 * std::max(camera_.fx, camera_.fy) * radius / c.z() + 2.0;
    reach.emplace_back(px->x(), px->y(), r_px * r_px);
    x0 = std::min(x0, px->x() - r_px), y0 = std::min(y0, px->y() - r_px);
    x1 = std::max(x1, px->x() + r_px), y1 = std::max(y1, px->y() + r_px);
  }
  if (x1 < 0 || y1 < 0 || x0 >= w_ || y0 >= h_) return {};
  const Rect r = ClipEven(x0, y0, x1, y1);
  if (r.empty()) return {};
  const Look& look = scene_.look;
  const Rgb albedo = look.ball;
  const Eigen::Vector3d light = camera_.cam_from_world.rotation * look.light;
  const int samples_t = static_cast<int>(centres.size());
  // Rays a pixel on a 4x4 stratified subpixel pattern, the cells cycling against the time
  // samples: ball_min_samples of them, or one a time sample. A long streak (more time samples
  // than cells) takes every one of the 16 cells at every time sample instead: with one ray a
  // sample the cells' cycle repeated along the streak and drew it as dashes 16 px apart, a
  // pattern no camera makes (a webcam's or a phone's streak; decided 2026-12-02).
  const bool every_cell = samples_t > 16;
  const int samples = every_cell ? 16 * samples_t : std::max(options_.ball_min_samples, samples_t);
  const std::size_t n = static_cast<std::size_t>(w_) * h_;
  int64_t sphere_hits = 0, shown_hits = 0;
  std::vector<int> near;
  for (int v = r.y0; v < r.y1; ++v) {
    for (int u = r.x0; u < r.x1; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w_ + u;
      const float depth = work_depth_[i];
      float sy = 0, su = 0, sv = 0;
      int hits = 0;
      // A long streak: only the time samples whose disc can reach this pixel (the others' rays
      // all miss, and count as misses).
      int rays = samples;
      if (every_cell) {
        near.clear();
        for (int k = 0; k < samples_t; ++k) {
          const double dx = u - reach[k].x(), dy = v - reach[k].y();
          if (dx * dx + dy * dy <= reach[k].z()) near.push_back(k);
        }
        if (near.empty()) continue;
        rays = 16 * static_cast<int>(near.size());
      }
      const int per_cell = every_cell ? static_cast<int>(near.size()) : 1;
      Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
      for (int s = 0; s < rays; ++s) {
        if (s % per_cell == 0) {
          const int cell = every_cell ? s / per_cell : (s * 11) % 16;
          const double du = ((cell % 4) + 0.5) / 4.0 - 0.5,
                       dv = ((cell >> 2) + 0.5) / 4.0 - 0.5;  // row of the grid
          const Eigen::Vector2d nrm = Normalized(u + du, v + dv);
          d = {nrm.x(), nrm.y(), 1.0};
        }
        const Eigen::Vector3d& c = centres[every_cell ? near[s % per_cell] : s % samples_t];
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
        Rgb col = Shade(albedo, normal, light, look.ball_ambient);
        const float spec = static_cast<float>(
            look.ball_specular * std::pow(std::max(0.0, reflect.dot(view)), look.shininess));
        col = {col.r + spec, col.g + spec, col.b + spec};
        float yy, uu, vv;
        ToYuv(col, look, &yy, &uu, &vv);
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
  // The defocus spreads what was drawn by the kernel's radius.
  const int m = static_cast<int>(kernel_.size()) / 2;
  for (const Rect& r : dirty_)
    WriteRect(ClipEven(r.x0 - m, r.y0 - m, r.x1 + m - 1, r.y1 + m - 1), out);
  const Look& look = scene_.look;
  if (look.drift > 0.0) {
    // Auto-exposure drifting slowly: every level scaled about black (luma) and grey (chroma).
    const double g = 1.0 + look.drift * std::sin(2.0 * M_PI * content.t / look.drift_period_s);
    std::array<uint8_t, 256> luma{}, chroma{};
    for (int x = 0; x < 256; ++x) {
      luma[x] = Clamp8(static_cast<float>(16.0 + g * (x - 16.0)));
      chroma[x] = Clamp8(static_cast<float>(128.0 + g * (x - 128.0)));
    }
    uint8_t* bytes = out->bytes().data();
    const std::size_t luma_size = static_cast<std::size_t>(w_) * h_;
    for (std::size_t i = 0; i < luma_size; ++i) bytes[i] = luma[bytes[i]];
    for (std::size_t i = luma_size; i < out->bytes().size(); ++i) bytes[i] = chroma[bytes[i]];
  }
  AddNoise(frame_index, out);
  return visible;
}

}  // namespace p4::sim
