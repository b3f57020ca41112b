// How a simulated hall looks (beyond the paper: the detector must hold in halls it has never
// seen). Everything that sets the colours and the light of a scene, drawn from a seed or taken
// from a named preset: the light's direction, strength and ambient share (overhead lamps give a
// bright top and a shaded bottom), a specular highlight on the ball, white balance, exposure and
// its slow auto-exposure drift; the colours of the ball (orange shades, white, yellow), the table
// (blue, green, black), the floor, the walls and the barriers; distractors (banners, lettering,
// shirts and shoes of the ball's colour, a second ball lying on the floor, fast arms) and lamps
// or windows in view.
//
// Colours are RGB in [0, 1] as the camera encodes them (values above 1 are emitted light and clip
// to white). World frame of DESIGN.md, metres.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace p4::sim {

struct Rgb {
  float r = 0.0f, g = 0.0f, b = 0.0f;
};

// A banner hung on a wall: a coloured rectangle with blocks of lettering.
struct Banner {
  int wall = 0;        // 0: x = -room, 1: x = +room, 2: y = -room, 3: y = +room
  double along = 0.0;  // centre along the wall (y for walls 0-1, x for 2-3), metres
  double z = 0.5;      // centre height above the table top, metres
  double width = 3.0, height = 0.8;
  Rgb color{0.95f, 0.45f, 0.1f};
  Rgb lettering{0.97f, 0.97f, 0.97f};
};

// An emitting rectangle: a lamp on the ceiling or a window in a wall (clips to white).
struct Lamp {
  bool ceiling = true;  // else on wall `wall` (as Banner::wall)
  int wall = 0;
  Eigen::Vector2d centre{0.0, 0.0};  // ceiling: (x, y); wall: (along, z)
  Eigen::Vector2d size{1.2, 0.3};
  float brightness = 1.6f;  // times white
};

struct Look {
  std::string name = "club";

  // Light: a main light from `light` (unit, towards the light) with the rest ambient.
  Eigen::Vector3d light = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();
  double ambient = 0.55;        // share of ambient light on the hall's surfaces
  double ball_ambient = 0.8;    // on the ball (many lamps light a matte ball from all round)
  double ball_specular = 0.08;  // strength of the highlight on the ball
  double shininess = 30.0;
  Rgb white_balance{1.0f, 1.0f, 1.0f};  // per-channel gains of the camera
  double gain = 1.0;                    // exposure: scales every colour
  double drift = 0.0;                   // auto-exposure drift: gain varies by +-drift
  double drift_period_s = 17.0;

  Rgb ball{1.0f, 0.42f, 0.05f};
  Rgb table{0.05f, 0.17f, 0.36f};
  Rgb lines{0.93f, 0.93f, 0.93f};
  Rgb floor{0.40f, 0.17f, 0.13f};
  Rgb wall{0.72f, 0.70f, 0.64f};
  Rgb barrier{0.08f, 0.10f, 0.28f};
  Rgb barrier_lettering{0.08f, 0.10f, 0.28f};  // = barrier: no lettering
  Rgb ceiling{0.85f, 0.85f, 0.86f};
  Rgb shirt_a{0.12f, 0.16f, 0.42f}, shirt_b{0.13f, 0.13f, 0.14f};
  Rgb shoes{0.9f, 0.9f, 0.9f};
  Rgb skin{0.82f, 0.6f, 0.5f};
  Rgb shorts{0.08f, 0.08f, 0.1f};

  std::vector<Banner> banners;
  std::vector<Lamp> lamps;
  std::optional<Eigen::Vector3d>
      spare_ball;          // a second ball lying still (centre), e.g. on the floor
  double arm_swing = 0.0;  // how far the players' arms swing, metres

  // Does the look's ball read as white (for the tracker's default colour hint).
  bool white_ball() const;
  bool IsValid(std::string* error) const;
};

// Today's club hall: red-brown floor, light walls with a dark barrier band, a blue table, an
// orange (or white) ball, a soft light from above one side.
Look ClubLook(bool orange_ball = true);

// Named presets: "club", "overhead" (lamps straight above: bright top, dark bottom of the ball,
// green table), "banner" (an orange banner on the wall behind a player, a ball-coloured shirt and
// shoes), "white" (white ball, light walls, lamps and windows in view, white lettering),
// "broadcast" (dark hall, white ball, white logos along the barriers), "dim" (a dark hall with
// auto-exposure drifting). Throws p4::Error for another name.
Look PresetLook(const std::string& name);
std::vector<std::string> PresetLookNames();

// The ball colours of the presets: "orange", "white" or "yellow" (throws p4::Error otherwise).
Rgb BallColour(const std::string& name);

// A look drawn from a seed: every field above across the range real halls show. `ball` may be
// "any", "orange", "white" or "yellow".
Look RandomLook(uint64_t seed, const std::string& ball = "any");

}  // namespace p4::sim
