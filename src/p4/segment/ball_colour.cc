#include "p4/segment/ball_colour.h"

#include <algorithm>
#include <cmath>

namespace p4::segment {

BallColour BallColour::Orange() { return BallColour{}; }

BallColour BallColour::White() {
  BallColour c;
  c.lit = {222.0f, 126.0f, 128.0f};
  return c;
}

BallColour BallColour::Yellow() {
  BallColour c;
  c.lit = {190.0f, 50.0f, 152.0f};
  return c;
}

bool BallColour::Named(const std::string& name, BallColour* out) {
  if (name == "orange") {
    *out = Orange();
    return true;
  }
  if (name == "white") {
    *out = White();
    return true;
  }
  if (name == "yellow") {
    *out = Yellow();
    return true;
  }
  return false;
}

bool BallColour::IsValid(std::string* error) const {
  const auto in = [](float x) { return x >= 0.0f && x <= 255.0f; };
  if (!in(lit.y) || !in(lit.u) || !in(lit.v) || lit.y < 24.0f) {
    if (error) *error = "the ball's colour must be 8-bit YUV with Y >= 24";
    return false;
  }
  return true;
}

bool UnmixOptions::IsValid(std::string* error) const {
  if (!(chroma_weight > 0.0) || !(min_shade > 0.0 && max_shade > min_shade) ||
      !(neutral_chroma >= 0.0)) {
    if (error)
      *error =
          "unmix: need a positive chroma weight, 0 < min shade < max shade, neutral chroma >= 0";
    return false;
  }
  return true;
}

Unmixed Unmix(const Yuv& o, const Yuv& bg, const BallColour& ball, const UnmixOptions& options) {
  const double w = std::sqrt(options.chroma_weight);
  // Weighted vectors: d = o - bg, e1 = K - bg, e2 = lit - K.
  const double d[3] = {o.y - bg.y, w * (o.u - bg.u), w * (o.v - bg.v)};
  const Yuv& k = kBlack;
  const double e1[3] = {k.y - bg.y, w * (k.u - bg.u), w * (k.v - bg.v)};
  const double e2[3] = {ball.lit.y - k.y, w * (ball.lit.u - k.u), w * (ball.lit.v - k.v)};
  const auto dot = [](const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  Unmixed r;
  r.difference = std::sqrt(dot(d, d));
  const double a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
  const double b1 = dot(e1, d), b2 = dot(e2, d);
  const double det = a11 * a22 - a12 * a12;
  double a = 0.0, b = 0.0;  // d ~ a e1 + b e2, b = a s
  if (det > 1e-3 * a11 * a22 && a11 > 1e-6) {
    a = (a22 * b1 - a12 * b2) / det;
    b = (a11 * b2 - a12 * b1) / det;
  }
  const auto near_neutral = [&](const Yuv& c) {
    return std::hypot(c.u - k.u, c.v - k.v) < options.neutral_chroma;
  };
  const bool degenerate =
      det <= 1e-3 * a11 * a22 || a11 <= 1e-6 || (near_neutral(ball.lit) && near_neutral(bg));
  double s = !degenerate && std::abs(a) > 1e-6 ? b / a : 1.0;
  if (degenerate || !(s >= options.min_shade && s <= options.max_shade)) {
    // Shading cannot be told apart (s = 1), or is out of range (the nearest bound): the share
    // for that shading alone, and the residual says how badly it fits.
    s = degenerate ? 1.0 : std::clamp(s, options.min_shade, options.max_shade);
    const double f[3] = {e1[0] + s * e2[0], e1[1] + s * e2[1], e1[2] + s * e2[2]};
    const double ff = dot(f, f);
    a = ff > 1e-6 ? dot(f, d) / ff : 0.0;
    b = a * s;
  }
  r.alpha = a;
  r.shade = std::abs(a) > 1e-6 ? b / a : 1.0;
  double res = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double e = d[k] - a * e1[k] - b * e2[k];
    res += e * e;
  }
  r.residual = std::sqrt(res);
  return r;
}

}  // namespace p4::segment
