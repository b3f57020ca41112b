#include "p4/track/epipolar_search.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "p4/geometry/epipolar.h"
#include "p4/geometry/sphere_depth.h"
#include "p4/geometry/triangulation.h"

namespace p4::track {

bool EpipolarSearchOptions::IsValid(std::string* error) const {
  if (!(depth_ratio > 1.0) || !(max_size_ratio > 1.0) || !(max_elongation >= 1.0)) {
    if (error) *error = "epipolar search: depth_ratio and max_size_ratio above 1, elongation >= 1";
    return false;
  }
  if (!(step_radii > 0.0) || max_fits < 1 || !(epipolar_px > 0.0) || !(ball_radius > 0.0)) {
    if (error) *error = "epipolar search: step, fits, epipolar_px and ball radius must be positive";
    return false;
  }
  if (!(min_chroma >= 0.0) || !(max_hue_deg > 0.0 && max_hue_deg <= 180.0)) {
    if (error) *error = "epipolar search: min_chroma >= 0 and max_hue_deg in (0, 180]";
    return false;
  }
  if (!(half_length > 0.0) || !(half_width > 0.0) || !(max_z > floor_z)) {
    if (error) *error = "epipolar search: the hall must have a size";
    return false;
  }
  if (!(circle_min_diameter_px >= 0.0) || !(circle_min_chroma >= 0.0)) {
    if (error)
      *error = "epipolar search: circle_min_diameter_px and circle_min_chroma must be >= 0";
    return false;
  }
  return edge.IsValid(error) && circle.IsValid(error);
}

namespace {

// The distance of a colour's (U, V) from grey.
double Chroma(const double colour[3]) { return std::hypot(colour[1] - 128.0, colour[2] - 128.0); }

// Whether `colour` (at `at`) differs from the ring `reach` px around it by the edge fit's
// contrast.
bool StandsOut(const ImageView& image, const Eigen::Vector2d& at, const double colour[3],
               double reach, const segment::EdgeCentreOptions& edge) {
  std::array<std::array<double, 4>, 3> ring{};
  const std::array<Eigen::Vector2d, 4> offsets{
      Eigen::Vector2d(reach, 0.0), Eigen::Vector2d(-reach, 0.0), Eigen::Vector2d(0.0, reach),
      Eigen::Vector2d(0.0, -reach)};
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    double c[3];
    const Eigen::Vector2d p = at + offsets[i];
    if (!segment::ColourAt(image, p.x(), p.y(), c)) return false;
    for (std::size_t channel = 0; channel < 3; ++channel) ring[channel][i] = c[channel];
  }
  double middle[3];
  for (std::size_t channel = 0; channel < 3; ++channel) {
    std::sort(ring[channel].begin(), ring[channel].end());
    middle[channel] = 0.5 * (ring[channel][1] + ring[channel][2]);
  }
  return segment::ColourDistance(colour, middle, edge.chroma_weight) >= edge.min_contrast;
}

}  // namespace

bool SameHue(const double colour_a[3], const double colour_b[3], double min_chroma,
             double max_hue_deg) {
  const double ua = colour_a[1] - 128.0, va = colour_a[2] - 128.0;
  const double ub = colour_b[1] - 128.0, vb = colour_b[2] - 128.0;
  const double ca = Chroma(colour_a), cb = Chroma(colour_b);
  if (ca < min_chroma) return cb < 2.0 * min_chroma;  // grey wants grey
  if (cb < min_chroma) return false;
  const double cosine = (ua * ub + va * vb) / (ca * cb);
  return cosine >= std::cos(max_hue_deg * M_PI / 180.0);
}

std::optional<EpipolarFind> SearchAlongEpipolar(const Camera& a, const Eigen::Vector2d& pixel_a,
                                                double diameter_a, const double colour_a[3],
                                                const Camera& b, const ImageView& image_b,
                                                const EpipolarSearchOptions& o) {
  if (!o.grey_balls && Chroma(colour_a) < o.min_chroma) {
    return std::nullopt;
  }
  const auto placed =
      PointFromSphereImage(a, pixel_a, diameter_a, EllipseAxis::kAcrossRadius, o.ball_radius);
  if (!placed) return std::nullopt;
  const Eigen::Vector3d origin = a.Center();
  const Eigen::Vector3d direction = a.RayDirection(pixel_a);
  const double near = placed->distance / o.depth_ratio, far = placed->distance * o.depth_ratio;
  const auto in_hall = [&](const Eigen::Vector3d& p) {
    return std::abs(p.x()) <= o.half_length && std::abs(p.y()) <= o.half_width &&
           p.z() >= o.floor_z && p.z() <= o.max_z;
  };
  // The circle from single rays where the pair fit fails (circle_min_diameter_px, _chroma).
  const bool circles = o.circle_min_diameter_px > 0.0 && Chroma(colour_a) >= o.circle_min_chroma;
  std::optional<EpipolarFind> best;
  std::vector<Eigen::Vector2d> tried;  // fits' centres already judged
  int fits = 0, distinct = 0;
  const double shortest = (far - near) / o.max_fits;
  for (double s = near; s <= far;) {
    const Eigen::Vector3d x = origin + s * direction;
    const auto q = b.Project(x);
    const double expected = SphereDiameterPx(b, x, o.ball_radius);
    // The next start a fraction of the ball's size on along the line.
    double step = shortest;
    if (q && expected > 0.0) {
      const auto q2 = b.Project(origin + (s + 1e-3 * s) * direction);
      if (q2) {
        const double rate = (*q2 - *q).norm() / (1e-3 * s);  // px per metre along the ray
        if (rate > 0.0) step = std::max(step, o.step_radii * 0.5 * expected / rate);
      }
    }
    s += step;
    if (!q || !(expected > 0.0) || !in_hall(x) || !b.InImage(*q, 0.5 * expected)) continue;
    // A start within half a radius of the ball's centre lies on the ball: of its hue, and apart
    // from the ring the fit's rays end on (the middle two of 4 samples there, per channel).
    double start[3];
    if (!segment::ColourAt(image_b, q->x(), q->y(), start) ||
        !SameHue(colour_a, start, o.min_chroma, o.max_hue_deg) ||
        !StandsOut(image_b, *q, start, o.edge.reach * 0.5 * expected + o.edge.reach_margin_px,
                   o.edge)) {
      continue;
    }
    ++fits;
    auto e = segment::MeasureEdgeCentre(image_b, q->x(), q->y(), 0.5 * expected, o.edge);
    if (!e && circles && expected >= o.circle_min_diameter_px) {
      e = segment::MeasureEdgeCircle(image_b, q->x(), q->y(), 0.5 * expected, o.circle);
    }
    if (!e || !(e->minor_diameter > 0.0) ||
        !(e->major_diameter <= o.max_elongation * e->minor_diameter)) {
      continue;
    }
    const Eigen::Vector2d found(e->cx, e->cy);
    if ((found - *q).norm() > expected) continue;
    if (std::any_of(tried.begin(), tried.end(),
                    [&](const Eigen::Vector2d& p) { return (p - found).norm() < 1.0; })) {
      continue;
    }
    tried.push_back(found);
    if (EpipolarDistance(a, pixel_a, b, found) > o.epipolar_px) continue;
    const std::array<Ray, 2> rays{Ray{origin, direction}, Ray{b.Center(), b.RayDirection(found)}};
    const auto point = TriangulateRays(rays);
    if (!point || !in_hall(point->point)) continue;
    const double expected_b = SphereDiameterPx(b, point->point, o.ball_radius);
    const double expected_a = SphereDiameterPx(a, point->point, o.ball_radius);
    if (!(expected_a > 0.0) || !(expected_b > 0.0)) continue;
    const double ratio_b = e->minor_diameter / expected_b, ratio_a = diameter_a / expected_a;
    if (ratio_b > o.max_size_ratio || ratio_b < 1.0 / o.max_size_ratio || ratio_a > o.depth_ratio ||
        ratio_a < 1.0 / o.depth_ratio) {
      continue;
    }
    if (!SameHue(colour_a, e->colour, o.min_chroma, o.max_hue_deg)) continue;
    const double misfit = std::abs(std::log(ratio_b));
    // Two balls on one segment, a diameter or more apart: the view cannot tell which.
    if (best && (best->pixel - found).norm() >= std::min(best->diameter_px, e->minor_diameter)) {
      ++distinct;
    }
    if (!best || misfit < best->size_misfit) {
      best = EpipolarFind{found, e->minor_diameter, point->point, misfit, 0};
    }
  }
  if (distinct > 0) return std::nullopt;
  if (best) best->fits = fits;
  return best;
}

}  // namespace p4::track
