#include "p4/sim/look.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "p4/core/error.h"
#include "p4/core/table.h"

namespace p4::sim {
namespace {

bool ColourOk(const Rgb& c) {
  const auto ok = [](float x) { return x >= 0.0f && x <= 4.0f; };
  return ok(c.r) && ok(c.g) && ok(c.b);
}

Rgb Grey(float level) { return {level, level, level}; }

constexpr Rgb kOrange{1.0f, 0.42f, 0.05f};
constexpr Rgb kWhiteBall{0.95f, 0.95f, 0.92f};

// Uniform draws from one engine.
struct Draw {
  std::mt19937_64 rng;
  double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  float F(double lo, double hi) { return static_cast<float>(U(lo, hi)); }
  int I(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
  bool P(double p) { return U(0.0, 1.0) < p; }
  // `c` with each channel scaled by up to +-`k` (a shade of the same colour).
  Rgb Shade(const Rgb& c, double k) {
    const float s = F(1.0 - k, 1.0 + k);
    return {std::clamp(c.r * s * F(0.95, 1.05), 0.0f, 1.0f),
            std::clamp(c.g * s * F(0.95, 1.05), 0.0f, 1.0f),
            std::clamp(c.b * s * F(0.95, 1.05), 0.0f, 1.0f)};
  }
  template <typename T>
  const T& Pick(const std::vector<T>& v) {
    return v[static_cast<std::size_t>(I(0, static_cast<int>(v.size()) - 1))];
  }
};

}  // namespace

Rgb BallColour(const std::string& name) {
  if (name == "orange") return kOrange;
  if (name == "white") return kWhiteBall;
  if (name == "yellow") return {0.97f, 0.86f, 0.18f};
  throw Error("ball '" + name + "': use orange, white or yellow");
}

bool Look::white_ball() const { return ball.b > 0.6f * ball.r && ball.g > 0.6f * ball.r; }

bool Look::IsValid(std::string* error) const {
  const auto fail = [&](const std::string& what) {
    if (error) *error = "look '" + name + "': " + what;
    return false;
  };
  if (!(std::abs(light.norm() - 1.0) < 1e-6)) return fail("light must be a unit vector");
  if (!(ambient >= 0.0 && ambient <= 1.0) || !(ball_ambient >= 0.0 && ball_ambient <= 1.0)) {
    return fail("ambient shares must be in [0, 1]");
  }
  if (!(ball_specular >= 0.0 && ball_specular <= 2.0) || !(shininess >= 1.0)) {
    return fail("specular must be in [0, 2] and shininess >= 1");
  }
  if (!(gain > 0.0 && gain <= 4.0) || !(drift >= 0.0 && drift < 1.0) || !(drift_period_s > 0.0)) {
    return fail("gain must be in (0, 4], drift in [0, 1), drift period > 0");
  }
  for (const Rgb& c : {white_balance, ball, table, lines, floor, wall, barrier, barrier_lettering,
                       ceiling, shirt_a, shirt_b, shoes, skin, shorts}) {
    if (!ColourOk(c)) return fail("colours must be in [0, 4]");
  }
  for (const Banner& b : banners) {
    if (b.wall < 0 || b.wall > 3 || !(b.width > 0 && b.height > 0) || !ColourOk(b.color)) {
      return fail("a banner needs a wall 0-3, a positive size and a colour");
    }
  }
  for (const Lamp& l : lamps) {
    if (l.wall < 0 || l.wall > 3 || !(l.size.minCoeff() > 0) || !(l.brightness > 0)) {
      return fail("a lamp needs a wall 0-3, a positive size and brightness");
    }
  }
  if (!(arm_swing >= 0.0 && arm_swing <= 1.0)) return fail("arm swing must be in [0, 1] m");
  return true;
}

Look ClubLook(bool orange_ball) {
  Look look;
  look.name = "club";
  if (!orange_ball) look.ball = kWhiteBall;
  return look;
}

std::vector<std::string> PresetLookNames() {
  return {"club", "overhead", "banner", "white", "broadcast", "dim"};
}

Look PresetLook(const std::string& name) {
  Look look = ClubLook();
  look.name = name;
  if (name == "club") return look;
  if (name == "overhead") {
    // Lamps straight above: the ball's top is lit, its bottom in shade; a green table.
    look.light = Eigen::Vector3d(0.05, 0.1, 1.0).normalized();
    look.ambient = 0.45;
    look.ball_ambient = 0.35;
    look.ball_specular = 0.25;
    look.table = {0.06f, 0.30f, 0.16f};
    for (double x : {-2.5, 0.0, 2.5}) {
      for (double y : {-1.5, 1.5}) look.lamps.push_back({true, 0, {x, y}, {1.2, 0.25}, 1.8f});
    }
    return look;
  }
  if (name == "banner") {
    // Ball-coloured things that are not the ball: a banner behind player B, a shirt, shoes.
    look.banners.push_back({1, 0.0, 0.6, 4.0, 1.0, {0.98f, 0.48f, 0.1f}, {0.97f, 0.97f, 0.97f}});
    look.banners.push_back({2, -2.0, 0.4, 3.0, 0.7, {0.95f, 0.4f, 0.08f}, {0.1f, 0.1f, 0.1f}});
    look.shirt_b = {0.95f, 0.45f, 0.12f};
    look.shoes = {1.0f, 0.45f, 0.1f};
    look.arm_swing = 0.4;
    return look;
  }
  if (name == "white") {
    // A white ball in a bright hall: light walls, lamps and windows in view, white lettering.
    look.ball = kWhiteBall;
    look.wall = {0.88f, 0.88f, 0.86f};
    look.floor = {0.62f, 0.62f, 0.64f};
    look.barrier = {0.12f, 0.2f, 0.5f};
    look.barrier_lettering = {0.97f, 0.97f, 0.97f};
    look.ceiling = {0.92f, 0.92f, 0.92f};
    look.shoes = {0.97f, 0.97f, 0.97f};
    look.shirt_a = {0.9f, 0.9f, 0.92f};
    for (double x : {-3.0, 0.0, 3.0}) look.lamps.push_back({true, 0, {x, 0.0}, {1.5, 0.3}, 2.0f});
    look.lamps.push_back({false, 3, {-2.0, 1.2}, {1.5, 1.2}, 1.5f});
    look.lamps.push_back({false, 2, {2.0, 1.2}, {1.5, 1.2}, 1.5f});
    return look;
  }
  if (name == "broadcast") {
    // A dark hall lit for television: white ball, white logos along the barriers.
    look.ball = kWhiteBall;
    look.light = Eigen::Vector3d(0.0, -0.3, 1.0).normalized();
    look.floor = {0.12f, 0.14f, 0.3f};
    look.wall = {0.05f, 0.05f, 0.07f};
    look.barrier = {0.1f, 0.12f, 0.4f};
    look.barrier_lettering = {0.98f, 0.98f, 0.98f};
    look.ceiling = {0.05f, 0.05f, 0.05f};
    look.banners.push_back({1, 0.0, 0.3, 5.0, 0.6, {0.1f, 0.12f, 0.4f}, {0.98f, 0.98f, 0.98f}});
    look.banners.push_back({0, 0.0, 0.3, 5.0, 0.6, {0.1f, 0.12f, 0.4f}, {0.98f, 0.98f, 0.98f}});
    return look;
  }
  if (name == "dim") {
    // A poorly lit hall with the camera's auto-exposure drifting.
    look.gain = 0.7;
    look.drift = 0.15;
    look.drift_period_s = 6.0;
    look.ambient = 0.65;
    look.white_balance = {1.12f, 1.0f, 0.85f};
    return look;
  }
  throw Error("look '" + name +
              "': not a preset (club, overhead, banner, white, broadcast, dim, "
              "or random)");
}

Look RandomLook(uint64_t seed, const std::string& ball) {
  Draw d{std::mt19937_64(seed * 0x9E3779B97F4A7C15ull + 0x1234567ull)};
  Look look;
  look.name = "random";
  // Light.
  const double elevation = d.U(35.0, 90.0) * M_PI / 180.0, azimuth = d.U(0.0, 2.0 * M_PI);
  look.light = Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                               std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  look.ambient = d.U(0.3, 0.75);
  look.ball_ambient = d.U(0.3, 0.85);
  look.ball_specular = d.U(0.0, 0.35);
  look.shininess = d.U(10.0, 60.0);
  look.white_balance = {d.F(0.85, 1.15), 1.0f, d.F(0.85, 1.15)};
  look.gain = d.U(0.75, 1.2);
  if (d.P(0.4)) {
    look.drift = d.U(0.03, 0.15);
    look.drift_period_s = d.U(5.0, 30.0);
  }
  // The ball.
  std::string kind = ball;
  if (kind == "any") kind = d.P(0.55) ? "orange" : (d.P(0.75) ? "white" : "yellow");
  if (kind == "orange") {
    look.ball = {d.F(0.95, 1.0), d.F(0.3, 0.55), d.F(0.0, 0.12)};
  } else if (kind == "white") {
    const float w = d.F(0.86, 0.97);
    look.ball = {w * d.F(0.98, 1.02), w, w * d.F(0.95, 1.0)};
  } else if (kind == "yellow") {
    look.ball = {d.F(0.92, 1.0), d.F(0.8, 0.92), d.F(0.1, 0.25)};
  } else {
    throw Error("ball '" + ball + "': use any, orange, white or yellow");
  }
  // The hall.
  const std::vector<Rgb> tables = {
      {0.05f, 0.17f, 0.36f}, {0.06f, 0.30f, 0.16f}, {0.06f, 0.06f, 0.07f}, {0.08f, 0.12f, 0.30f}};
  look.table = d.Shade(d.Pick(tables), 0.15);
  const std::vector<Rgb> floors = {
      {0.40f, 0.17f, 0.13f}, {0.35f, 0.35f, 0.36f}, {0.65f, 0.65f, 0.66f}, {0.55f, 0.38f, 0.22f},
      {0.10f, 0.35f, 0.20f}, {0.10f, 0.20f, 0.45f}, {0.80f, 0.79f, 0.76f}, {0.55f, 0.22f, 0.12f}};
  look.floor = d.Shade(d.Pick(floors), 0.15);
  const std::vector<Rgb> walls = {
      {0.90f, 0.90f, 0.88f}, {0.72f, 0.70f, 0.64f}, {0.10f, 0.14f, 0.35f}, {0.05f, 0.05f, 0.06f},
      {0.55f, 0.40f, 0.25f}, {0.80f, 0.74f, 0.60f}, {0.60f, 0.62f, 0.66f}};
  look.wall = d.Shade(d.Pick(walls), 0.1);
  const std::vector<Rgb> barriers = {{0.08f, 0.10f, 0.28f},
                                     {0.05f, 0.05f, 0.05f},
                                     {0.06f, 0.28f, 0.12f},
                                     {0.55f, 0.08f, 0.08f},
                                     {0.2f, 0.2f, 0.22f}};
  look.barrier = d.Shade(d.Pick(barriers), 0.15);
  look.barrier_lettering = d.P(0.5) ? Grey(d.F(0.85, 0.98)) : look.barrier;
  look.ceiling = Grey(d.F(0.3, 0.9));
  look.lines = Grey(d.F(0.85, 0.95));
  // People: skin from dark to light, clothes of any colour, sometimes the ball's.
  const float s = d.F(0.0, 1.0);
  look.skin = {0.35f + 0.5f * s, 0.22f + 0.42f * s, 0.15f + 0.38f * s};
  const auto clothes = [&]() -> Rgb {
    if (d.P(0.2)) return d.Shade(look.ball, 0.12);
    return {d.F(0.05, 0.9), d.F(0.05, 0.9), d.F(0.05, 0.9)};
  };
  look.shirt_a = clothes();
  look.shirt_b = clothes();
  look.shorts = d.P(0.5) ? Grey(d.F(0.05, 0.2)) : clothes();
  look.shoes = d.P(0.5) ? Grey(d.F(0.85, 0.97)) : clothes();
  look.arm_swing = d.U(0.0, 0.5);
  // Distractors and lights in view.
  const int banners = d.I(0, 3);
  for (int k = 0; k < banners; ++k) {
    Banner b;
    b.wall = d.I(0, 3);
    b.along = d.U(-3.0, 3.0);
    b.z = d.U(0.1, 1.2);
    b.width = d.U(1.5, 5.0);
    b.height = d.U(0.5, 1.2);
    b.color =
        d.P(0.5) ? d.Shade(look.ball, 0.1) : Rgb{d.F(0.05, 0.95), d.F(0.05, 0.95), d.F(0.05, 0.95)};
    b.lettering = d.P(0.5) ? Grey(d.F(0.85, 0.98)) : Grey(d.F(0.02, 0.15));
    look.banners.push_back(b);
  }
  const int lamps = d.I(0, 6);
  for (int k = 0; k < lamps; ++k) {
    look.lamps.push_back(
        {true, 0, {d.U(-5.0, 5.0), d.U(-3.5, 3.5)}, {d.U(0.6, 1.6), d.U(0.2, 0.5)}, d.F(1.2, 2.5)});
  }
  if (d.P(0.3)) {
    look.lamps.push_back({false,
                          d.I(0, 3),
                          {d.U(-3.0, 3.0), d.U(0.8, 1.8)},
                          {d.U(1.0, 2.5), d.U(0.8, 1.5)},
                          d.F(1.1, 1.8)});
  }
  if (d.P(0.35)) {
    // A spare ball on the floor, outside the table's footprint.
    const double x = d.U(1.6, 3.5) * (d.P(0.5) ? 1 : -1), y = d.U(-2.5, 2.5);
    look.spare_ball = Eigen::Vector3d(x, y, table::kFloorZ + table::kBallRadius);
  }
  std::string why;
  if (!look.IsValid(&why)) throw Error(why);  // a bug in the draws above
  return look;
}

}  // namespace p4::sim
