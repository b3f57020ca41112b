// The ball's colour as a camera sees it, and how much of a pixel the ball covers (beyond the
// paper, whose fixed colour boxes miss a ball that is shaded, blurred or small).
//
// Model: a lit ball shows `lit` (8-bit YUV, BT.601 limited range); shading scales its light by
// s (0 = black, 1 = lit, > 1 for a highlight), so the ball's colour at a point is K + s (lit - K)
// with K black (16, 128, 128). A pixel that the ball covers for a share a of its area and of the
// exposure (anti-aliased edge, motion blur) shows the mix
//     o = (1 - a) bg + a (K + s (lit - K)),
// with bg the background behind it. Unmix() solves for a and s by least squares (chroma
// weighted) and reports the residual: the pixel's evidence that it is the ball mixed with its
// background, whatever the shading or the blur. Pure.
#pragma once

#include <cmath>
#include <string>

namespace p4::segment {

struct Yuv {
  float y = 16.0f, u = 128.0f, v = 128.0f;
};

// K above: black, where every shade of every colour ends.
inline constexpr Yuv kBlack{16.0f, 128.0f, 128.0f};

struct BallColour {
  Yuv lit{137.0f, 65.0f, 200.0f};  // an orange ball under indoor light

  static BallColour Orange();
  static BallColour White();
  static BallColour Yellow();
  // "orange", "white" or "yellow"; false for another name.
  static bool Named(const std::string& name, BallColour* out);
  // Grey: the lit chroma within 30 levels of neutral (an orange or a yellow ball lies 80-100
  // levels away; a white ball under a tinted light 10-20). A white ball is a bright grey (its
  // lit side above 110; the simulator's white halls give 170-245): a dark grey is no ball's
  // colour (a shadow, a shoe).
  bool IsGrey() const { return std::hypot(lit.u - 128.0f, lit.v - 128.0f) < 30.0f; }
  bool IsWhite() const { return IsGrey() && lit.y > 110.0f; }
  bool IsValid(std::string* error) const;
  // The ball's colour at shading s: K + s (lit - K) (the model above).
  Yuv Shaded(float s) const {
    return {kBlack.y + s * (lit.y - kBlack.y), kBlack.u + s * (lit.u - kBlack.u),
            kBlack.v + s * (lit.v - kBlack.v)};
  }
};

struct Unmixed {
  double alpha = 0.0;       // the ball's share of the pixel (not clamped)
  double shade = 1.0;       // s above (meaningful when alpha is not small)
  double residual = 0.0;    // weighted distance of o from the model's best mix, levels
  double difference = 0.0;  // weighted |o - bg|, levels
};

struct UnmixOptions {
  double chroma_weight = 2.0;  // chroma counts this much more than luma (it shades less)
  double min_shade = 0.25, max_shade = 1.8;
  // Levels of chroma: where the ball's lit colour and the background both lie within this of
  // neutral (black's chroma), their chroma cannot tell the shading. A small ball's chroma is
  // smeared into its background's by the encoder's half-resolution chroma, and cameras' white
  // balances differ by as much: a white ball of 9 px showed (U, V) 126/129 in one camera and
  // 130/127, its grey wall's, in the other, against a learnt 126/129. Fitted there, the shading
  // follows those few levels (the ball taken for a fifth of a dark ball, or for none).
  double neutral_chroma = 6.0;

  bool IsValid(std::string* error) const;
};

// Solves o = (1 - a) bg + a (K + s (lit - K)) for a and s. Where the ball's colour and the
// background lie on one line through black (a white ball on a grey wall), or both within
// neutral_chroma of neutral, s is taken as 1.
Unmixed Unmix(const Yuv& observed, const Yuv& background, const BallColour& ball,
              const UnmixOptions& options = {});

}  // namespace p4::segment
