#include "p4/segment/ball_edge.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "p4/core/robust.h"
#include "p4/segment/pixel_access.h"

namespace p4::segment {
namespace {

double Bilinear(double a, double b, double c, double d, double fx, double fy) {
  return (1.0 - fy) * ((1.0 - fx) * a + fx * b) + fy * ((1.0 - fx) * c + fx * d);
}

}  // namespace

// Chroma samples are centred at 2i + 0.5, 2j + 0.5.
bool ColourAt(const ImageView& image, double x, double y, double out[3]) {
  if (!(x >= 0.0 && y >= 0.0 && x <= image.width - 1.0 && y <= image.height - 1.0)) return false;
  const int x0 = std::min(static_cast<int>(x), image.width - 2);
  const int y0 = std::min(static_cast<int>(y), image.height - 2);
  out[0] = Bilinear(internal::LumaAt(image, x0, y0), internal::LumaAt(image, x0 + 1, y0),
                    internal::LumaAt(image, x0, y0 + 1), internal::LumaAt(image, x0 + 1, y0 + 1),
                    x - x0, y - y0);
  const int cw = image.width / 2, ch = image.height / 2;  // whole chroma samples
  const double sx = std::clamp((x - 0.5) / 2.0, 0.0, cw - 1.0);
  const double sy = std::clamp((y - 0.5) / 2.0, 0.0, ch - 1.0);
  const int i0 = std::min(static_cast<int>(sx), std::max(0, cw - 2));
  const int j0 = std::min(static_cast<int>(sy), std::max(0, ch - 2));
  const int i1 = std::min(i0 + 1, cw - 1), j1 = std::min(j0 + 1, ch - 1);
  uint8_t u[4] = {128, 128, 128, 128}, v[4] = {128, 128, 128, 128};
  internal::ChromaAt(image, 2 * i0, 2 * j0, &u[0], &v[0]);
  internal::ChromaAt(image, 2 * i1, 2 * j0, &u[1], &v[1]);
  internal::ChromaAt(image, 2 * i0, 2 * j1, &u[2], &v[2]);
  internal::ChromaAt(image, 2 * i1, 2 * j1, &u[3], &v[3]);
  out[1] = Bilinear(u[0], u[1], u[2], u[3], sx - i0, sy - j0);
  out[2] = Bilinear(v[0], v[1], v[2], v[3], sx - i0, sy - j0);
  return true;
}

double ColourDistance(const double* a, const double* b, double chroma_weight) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) +
                   chroma_weight * ((a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
}

bool ShadeOptions::IsValid(std::string* error) const {
  if (!(symmetric_px >= 0.0) || !(max_share >= 0.0 && max_share < 1.0) || camera_min_views < 0 ||
      !(camera_agreement > 0.0 && camera_agreement <= 1.0)) {
    if (error) {
      *error =
          "shade: symmetric_px must be at least 0, max_share in [0, 1), camera_min_views at "
          "least 0 and camera_agreement in (0, 1]";
    }
    return false;
  }
  return true;
}

void FaintSideVote::Add(const double faint[2]) {
  const double norm = std::hypot(faint[0], faint[1]);
  if (!(norm > 0.0)) return;
  sum_[0] += faint[0] / norm;
  sum_[1] += faint[1] / norm;
  ++views_;
}

bool FaintSideVote::Agreed(const ShadeOptions& options, double out[2]) const {
  if (options.camera_min_views <= 0 || views_ < options.camera_min_views) return false;
  const double norm = std::hypot(sum_[0], sum_[1]);
  if (!(norm >= options.camera_agreement * views_)) return false;
  out[0] = sum_[0] / norm;
  out[1] = sum_[1] / norm;
  return true;
}

void UnshadeCentre(double width_px, const double faint[2], double expected_px,
                   const ShadeOptions& options, double* cx, double* cy) {
  if (!(expected_px > 0.0) || (faint[0] == 0.0 && faint[1] == 0.0)) return;
  const double lost = std::clamp(expected_px - width_px - options.symmetric_px, 0.0,
                                 options.max_share * expected_px);
  *cx += 0.5 * lost * faint[0];
  *cy += 0.5 * lost * faint[1];
}

namespace {

// Samples along a ray from (cx, cy): n colours (Y, U, V) at o.step_px apart. False when the
// ray leaves the image.
bool SampleRay(const ImageView& image, double cx, double cy, double ux, double uy, int n,
               const EdgeCentreOptions& o, double* colours) {
  for (int k = 0; k < n; ++k) {
    const double r = k * o.step_px;
    if (!ColourAt(image, cx + r * ux, cy + r * uy, colours + 3 * k)) return false;
  }
  return true;
}

// Distance along a sampled ray to the ball's edge; negative when the ray finds none.
// `background`: the colour beyond the ball on this ray. The profile is each sample's distance
// from it in colour (luma where the ball is brighter or darker, chroma where a dark orange ball
// and a blue table have the same luma).
double EdgeOnRay(const double* colours, int n, const double* background, double radius,
                 const EdgeCentreOptions& o, std::vector<double>* profile) {
  profile->resize(static_cast<std::size_t>(n));
  std::vector<double>& d = *profile;
  for (int k = 0; k < n; ++k) {
    d[static_cast<std::size_t>(k)] = ColourDistance(colours + 3 * k, background, o.chroma_weight);
  }
  const int inner_n = std::max(1, static_cast<int>(0.3 * radius / o.step_px));
  double inner = 0.0;
  for (int k = 0; k < inner_n; ++k) inner += d[static_cast<std::size_t>(k)];
  if (inner / inner_n < o.min_contrast) return -1.0;
  // The edge: where the distance has fallen halfway from the ball's, as it is just inside (w =
  // 1.5 px back along the ray), to the background's. The ball's shading falls inside the disc
  // slowly (less than half of what is left over w), so the dark half's edge is found where its
  // own level meets the background, not where the lit half's level would put it; a line beyond
  // the ball comes after the edge. A blur streak's ramp is crossed w before its end on both
  // opposite rays alike: the centre stays unbiased.
  const int back = std::max(1, static_cast<int>(std::lround(1.5 / o.step_px)));
  const auto above_half = [&](int k) {
    return d[static_cast<std::size_t>(k)] -
           0.5 * d[static_cast<std::size_t>(std::max(0, k - back))];
  };
  double previous = above_half(inner_n - 1);
  for (int k = inner_n; k < n; ++k) {
    const double now = above_half(k);
    if (now <= 0.0) {
      const double f = previous > 0.0 ? previous / (previous - now) : 0.0;
      return (k - 1 + f) * o.step_px;
    }
    previous = now;
  }
  return -1.0;
}

// Samples per ray for a ball of radius guess `radius` (px): to reach x the radius plus the margin.
int RaySamples(double radius, const EdgeCentreOptions& o) {
  return static_cast<int>(std::ceil((o.reach * radius + o.reach_margin_px) / o.step_px)) + 1;
}

// Each ray's edge from (cx, cy) along (ux, uy)[r] (negative: none) and its contrast inside the
// edge (for EdgeCentre::faint; `contrast` may be null), the rays' colours into `colours`
// (`sampled`: whether the ray stayed in the image). The background is the ring beyond the ball: per
// channel the median of all rays' last 2 px, and on each ray its own tail sample nearest to that
// unless even that one differs from the ring (a line or a shadow across some rays' ends is not
// their background). False when no ray stayed in the image.
bool RayEdges(const ImageView& image, double cx, double cy, double radius,
              const EdgeCentreOptions& o, const std::vector<double>& ux,
              const std::vector<double>& uy, std::vector<double>* colours,
              std::vector<uint8_t>* sampled, std::vector<double>* edges,
              std::vector<double>* contrast) {
  const int n = RaySamples(radius, o);
  const int tail = std::min(n, std::max(3, static_cast<int>(2.0 / o.step_px)));  // the last 2 px
  const int rays = static_cast<int>(ux.size());
  colours->resize(3 * static_cast<std::size_t>(n) * rays);
  sampled->assign(static_cast<std::size_t>(rays), 0);
  edges->assign(static_cast<std::size_t>(rays), -1.0);
  if (contrast) contrast->assign(static_cast<std::size_t>(rays), 0.0);
  for (int r = 0; r < rays; ++r) {
    const auto j = static_cast<std::size_t>(r);
    (*sampled)[j] = SampleRay(image, cx, cy, ux[j], uy[j], n, o, &(*colours)[3 * n * j]);
  }
  double median[3];
  std::vector<double> ring, profile;
  for (int channel = 0; channel < 3; ++channel) {
    ring.clear();
    for (int r = 0; r < rays; ++r) {
      if (!(*sampled)[static_cast<std::size_t>(r)]) continue;
      for (int k = n - tail; k < n; ++k) {
        ring.push_back((*colours)[3 * (static_cast<std::size_t>(n) * r + k) + channel]);
      }
    }
    if (ring.empty()) return false;
    median[channel] = MedianInPlace(ring);
  }
  for (int r = 0; r < rays; ++r) {
    const auto j = static_cast<std::size_t>(r);
    if (!(*sampled)[j]) continue;
    const double* c = &(*colours)[3 * static_cast<std::size_t>(n) * r];
    const double* background = c + 3 * (n - 1);
    double nearest = ColourDistance(background, median, o.chroma_weight);
    for (int k = n - tail; k < n - 1; ++k) {
      const double distance = ColourDistance(c + 3 * k, median, o.chroma_weight);
      if (distance < nearest) background = c + 3 * k, nearest = distance;
    }
    // A ray whose end lies on something else (a line, a shadow) takes the ring's colour.
    if (nearest > o.min_contrast) background = median;
    const double found = EdgeOnRay(c, n, background, radius, o, &profile);
    (*edges)[j] = found;
    if (contrast && found > 0.0) {
      const int k0 = static_cast<int>(std::ceil(found / 3.0 / o.step_px));
      const int k1 = std::min(n - 1, static_cast<int>(2.0 * found / 3.0 / o.step_px));
      double sum = 0.0;
      for (int k = k0; k <= k1; ++k) sum += profile[static_cast<std::size_t>(k)];
      (*contrast)[j] = k1 >= k0 ? sum / (k1 - k0 + 1) : 0.0;
    }
  }
  return true;
}

// Unit directions of `count` rays evenly round the circle (i and i + count / 2 opposite).
void RayDirections(int count, std::vector<double>* ux, std::vector<double>* uy) {
  ux->resize(static_cast<std::size_t>(count));
  uy->resize(ux->size());
  for (int r = 0; r < count; ++r) {
    const double a = 2.0 * M_PI * r / count;
    (*ux)[static_cast<std::size_t>(r)] = std::cos(a),
    (*uy)[static_cast<std::size_t>(r)] = std::sin(a);
  }
}

// The colour inside a fit of width `width_px`: every sampled ray's first samples (the rays start
// within settled_px of the centre, or at the last centre before it moved less than that).
void InsideColour(const std::vector<double>& colours, const std::vector<uint8_t>& sampled, int n,
                  double width_px, const EdgeCentreOptions& o, double out[3]) {
  const int inside =
      std::max(1, std::min(n, 1 + static_cast<int>(0.25 * std::max(width_px, 2.0) / o.step_px)));
  int count = 0;
  out[0] = out[1] = out[2] = 0.0;
  for (std::size_t r = 0; r < sampled.size(); ++r) {
    if (!sampled[r]) continue;
    for (int k = 0; k < inside; ++k, ++count) {
      for (int channel = 0; channel < 3; ++channel) {
        out[channel] += colours[3 * (static_cast<std::size_t>(n) * r + k) + channel];
      }
    }
  }
  for (int channel = 0; channel < 3; ++channel) out[channel] /= std::max(1, count);
}

}  // namespace

bool EdgeCentreOptions::IsValid(std::string* error) const {
  if (directions < 8 || directions % 2 != 0 || !(step_px > 0.0 && step_px <= 1.0) ||
      !(reach > 1.0) || !(reach_margin_px >= 1.0) || !(min_contrast >= 0.0) ||
      !(max_pair_residual_px > 0.0) || !(min_pair_share > 0.0 && min_pair_share <= 1.0) ||
      !(max_residual_px > 0.0) || !(chroma_weight >= 0.0) || iterations < 1 ||
      !(settled_px >= 0.0)) {
    if (error) {
      *error =
          "edge centre: need an even number of >= 8 directions, a step in (0, 1] px, reach > 1, "
          "a pair share in (0, 1], positive residual bounds, iterations >= 1, settled >= 0";
    }
    return false;
  }
  return true;
}

std::optional<EdgeCentre> MeasureEdgeCentre(const ImageView& image, double cx, double cy,
                                            double radius_px, const EdgeCentreOptions& o) {
  const double radius = std::max(1.0, radius_px);
  const int half = o.directions / 2;
  const int n = RaySamples(radius, o);
  std::vector<double> colours, edges, contrast;
  std::vector<uint8_t> sampled;
  std::vector<double> d(static_cast<std::size_t>(half)), extent(d.size());
  std::vector<uint8_t> use(d.size());
  // The rays' directions: i and i + half are opposite.
  std::vector<double> ux, uy;
  RayDirections(o.directions, &ux, &uy);
  EdgeCentre out;
  for (int iteration = 0; iteration < o.iterations; ++iteration) {
    if (!RayEdges(image, cx, cy, radius, o, ux, uy, &colours, &sampled, &edges, &contrast)) {
      return std::nullopt;
    }
    const auto edge = [&](int r) { return edges[static_cast<std::size_t>(r)]; };
    for (int i = 0; i < half; ++i) {
      const double r1 = edge(i), r2 = edge(i + half);
      const auto j = static_cast<std::size_t>(i);
      use[j] = r1 > 0.0 && r2 > 0.0;
      d[j] = 0.5 * (r1 - r2);  // the centre's offset along the ray
      extent[j] = r1 + r2;     // the shape's width along it
    }
    // d_i = offset . u_i by least squares, dropping pairs far from the fit.
    double ox = 0.0, oy = 0.0;
    int pairs = 0;
    double residual = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      double sxx = 0.0, sxy = 0.0, syy = 0.0, bx = 0.0, by = 0.0;
      for (int i = 0; i < half; ++i) {
        const auto j = static_cast<std::size_t>(i);
        if (!use[j]) continue;
        sxx += ux[j] * ux[j], sxy += ux[j] * uy[j], syy += uy[j] * uy[j];
        bx += d[j] * ux[j], by += d[j] * uy[j];
      }
      const double det = sxx * syy - sxy * sxy;
      if (!(det > 1e-6)) return std::nullopt;
      ox = (syy * bx - sxy * by) / det;
      oy = (sxx * by - sxy * bx) / det;
      pairs = 0;
      residual = 0.0;
      for (int i = 0; i < half; ++i) {
        const auto j = static_cast<std::size_t>(i);
        if (!use[j]) continue;
        const double e = d[j] - (ox * ux[j] + oy * uy[j]);
        if (pass == 0 && std::abs(e) > o.max_pair_residual_px) {
          use[j] = 0;
          continue;
        }
        ++pairs, residual += e * e;
      }
    }
    if (pairs < std::max(3.0, o.min_pair_share * half)) return std::nullopt;
    cx += ox, cy += oy;
    out.pairs = pairs;
    out.residual_px = std::sqrt(residual / pairs);
    if (out.residual_px > o.max_residual_px) return std::nullopt;
    // Rays cast again only when the centre moved enough to change where they cross the edge.
    if (std::hypot(ox, oy) < o.settled_px) break;
  }
  // The widths of the last rays' pairs that agree: a centred ellipse (a disc, a short streak) has
  // 4 / width^2 = P + Q cos 2a + R sin 2a along direction a; its axes from P, Q, R by least
  // squares (the rays' origin within settled_px of the centre shortens a width only to second
  // order).
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int i = 0; i < half; ++i) {
    const auto j = static_cast<std::size_t>(i);
    if (!use[j] || !(extent[j] > 0.0)) continue;
    const double a = 2.0 * M_PI * i / o.directions;
    const Eigen::Vector3d row(1.0, std::cos(2.0 * a), std::sin(2.0 * a));
    normal += row * row.transpose();
    rhs += row * (4.0 / (extent[j] * extent[j]));
  }
  const Eigen::Vector3d f = normal.ldlt().solve(rhs);
  const double q = std::hypot(f(1), f(2));
  out.minor_diameter = f(0) + q > 0.0 ? 2.0 / std::sqrt(f(0) + q) : 0.0;
  out.major_diameter = f(0) - q > 0.0 ? 2.0 / std::sqrt(f(0) - q) : 0.0;
  InsideColour(colours, sampled, n, out.minor_diameter, o, out.colour);
  // The faint side: the agreeing pairs' contrasts as a + b cos + c sin, by least squares.
  Eigen::Matrix3d contrast_normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d contrast_rhs = Eigen::Vector3d::Zero();
  int agreeing = 0;
  for (int i = 0; i < half; ++i) {
    if (!use[static_cast<std::size_t>(i)]) continue;
    ++agreeing;
    for (const int r : {i, i + half}) {
      const auto j = static_cast<std::size_t>(r);
      const Eigen::Vector3d row(1.0, ux[j], uy[j]);
      contrast_normal += row * row.transpose();
      contrast_rhs += row * contrast[j];
    }
  }
  if (agreeing >= 3) {
    const Eigen::Vector3d f = contrast_normal.ldlt().solve(contrast_rhs);
    const double b = std::hypot(f(1), f(2));
    if (b > 0.0) out.faint[0] = -f(1) / b, out.faint[1] = -f(2) / b;
  }
  out.cx = cx, out.cy = cy;
  return out;
}

bool EdgeCircleOptions::IsValid(std::string* error) const {
  if (!edge.IsValid(error)) return false;
  if (!(min_ray_share > 0.0 && min_ray_share <= 1.0) || !(max_ray_residual_px > 0.0) ||
      !(max_gap_deg > 0.0 && max_gap_deg <= 180.0)) {
    if (error) {
      *error =
          "edge circle: min_ray_share in (0, 1], max_ray_residual_px > 0, max_gap_deg in (0, 180]";
    }
    return false;
  }
  return true;
}

std::optional<EdgeCentre> MeasureEdgeCircle(const ImageView& image, double cx, double cy,
                                            double radius_px, const EdgeCircleOptions& options) {
  const EdgeCentreOptions& o = options.edge;
  const double radius = std::max(1.0, radius_px);
  const int rays = o.directions;
  const int n = RaySamples(radius, o);
  std::vector<double> colours, edges, ux, uy, found;
  std::vector<uint8_t> sampled, use(static_cast<std::size_t>(rays));
  RayDirections(rays, &ux, &uy);
  EdgeCentre out;
  double fitted_radius = radius;
  for (int iteration = 0; iteration < o.iterations; ++iteration) {
    if (!RayEdges(image, cx, cy, radius, o, ux, uy, &colours, &sampled, &edges, nullptr)) {
      return std::nullopt;
    }
    // Rays whose edge lies within half a radius guess of the median edge (a ray that ran along
    // the merged region finds its far end, or none).
    found.clear();
    for (double e : edges) {
      if (e > 0.0) found.push_back(e);
    }
    if (found.size() < 3) return std::nullopt;
    const double median = MedianInPlace(found);
    for (int r = 0; r < rays; ++r) {
      const double e = edges[static_cast<std::size_t>(r)];
      use[static_cast<std::size_t>(r)] = e > 0.0 && std::abs(e - median) <= 0.5 * radius;
    }
    // r_i = ox ux_i + oy uy_i + R by least squares; pass 0 drops rays far from the fit.
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    int agree = 0;
    double residual = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
      Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
      for (int r = 0; r < rays; ++r) {
        const auto j = static_cast<std::size_t>(r);
        if (!use[j]) continue;
        const Eigen::Vector3d row(ux[j], uy[j], 1.0);
        normal += row * row.transpose();
        rhs += row * edges[j];
      }
      if (!(normal.determinant() > 1e-6)) return std::nullopt;
      f = normal.ldlt().solve(rhs);
      agree = 0;
      residual = 0.0;
      for (int r = 0; r < rays; ++r) {
        const auto j = static_cast<std::size_t>(r);
        if (!use[j]) continue;
        const double e = edges[j] - (f(0) * ux[j] + f(1) * uy[j] + f(2));
        if (pass == 0 && std::abs(e) > options.max_ray_residual_px) {
          use[j] = 0;
          continue;
        }
        ++agree, residual += e * e;
      }
    }
    if (agree < 4 || !(f(2) > 0.0)) return std::nullopt;
    cx += f(0), cy += f(1);
    fitted_radius = f(2);
    out.pairs = agree;
    out.residual_px = std::sqrt(residual / agree);
    // Rays cast again from the new centre (the model is first order in the offset) until it
    // settles; the last fit is judged.
    if (std::hypot(f(0), f(1)) >= o.settled_px && iteration + 1 < o.iterations) continue;
    if (agree < options.min_ray_share * rays || out.residual_px > o.max_residual_px) {
      return std::nullopt;
    }
    // The widest gap between agreeing rays' directions (in steps of the rays).
    int gap = 0, last = -1, first = -1;
    for (int r = 0; r < rays; ++r) {
      if (!use[static_cast<std::size_t>(r)]) continue;
      if (last >= 0) gap = std::max(gap, r - last);
      if (first < 0) first = r;
      last = r;
    }
    gap = std::max(gap, first + rays - last);
    if (gap * 360.0 / rays > options.max_gap_deg + 1e-9) return std::nullopt;
    break;
  }
  out.minor_diameter = out.major_diameter = 2.0 * fitted_radius;
  InsideColour(colours, sampled, n, out.minor_diameter, o, out.colour);
  out.cx = cx, out.cy = cy;
  return out;
}

}  // namespace p4::segment
