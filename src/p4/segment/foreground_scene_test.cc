// The background detector on frames the simulator renders in memory, against the exact
// projection of the ball (its silhouette sampled by rays through each pixel, averaged over the
// exposure): named looks that break colour-only detection (shading, blur, small balls, white
// balls beside white lines, lamps, banners, shirts, logos) and a ball held still.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "p4/core/table.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_edge.h"
#include "p4/segment/ball_measure.h"
#include "p4/segment/blob_finder.h"
#include "p4/segment/color_classes.h"
#include "p4/segment/colour_learning.h"
#include "p4/segment/foreground_finder.h"
#include "p4/segment/streak_finder.h"
#include "p4/segment/streak_search.h"
#include "p4/sim/camera_layout.h"
#include "p4/sim/look.h"
#include "p4/sim/renderer.h"

namespace p4::segment {
namespace {

struct Silhouette {
  Eigen::Vector2d centre;  // coverage-weighted centre, px
  double area = 0.0;       // px^2, averaged over the exposure
  // Its width across its longest axis: 4 sqrt of the smallest eigenvalue of the coverage's
  // covariance (a disc's diameter; a streak's across the motion), px.
  double minor_diameter = 0.0;
};

// The exact image of the ball: coverage of each pixel by rays (8x8 a pixel) that hit the sphere,
// averaged over the exposure's samples.
Silhouette Exact(const Camera& camera, const std::vector<Eigen::Vector3d>& samples) {
  double sum = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (const Eigen::Vector3d& p : samples) {
    const Eigen::Vector3d c = camera.cam_from_world * p;
    const auto px = camera.Project(p);
    const double r_px = 1.5 * camera.fx * table::kBallRadius / c.z() + 2.0;
    for (int v = static_cast<int>(px->y() - r_px); v <= static_cast<int>(px->y() + r_px) + 1; ++v) {
      for (int u = static_cast<int>(px->x() - r_px); u <= static_cast<int>(px->x() + r_px) + 1;
           ++u) {
        for (int k = 0; k < 64; ++k) {
          const double du = (k % 8 + 0.5) / 8.0 - 0.5, dv = (k / 8 + 0.5) / 8.0 - 0.5;
          const Eigen::Vector2d n = camera.NormalizedFromPixel({u + du, v + dv});
          const Eigen::Vector3d d(n.x(), n.y(), 1.0);
          const double dc = d.dot(c), dd = d.squaredNorm();
          if (dc * dc - dd * (c.squaredNorm() - table::kBallRadius * table::kBallRadius) < 0.0) {
            continue;
          }
          const double w = 1.0 / 64.0 / samples.size(), x = u + du, y = v + dv;
          sum += w, sx += w * x, sy += w * y;
          sxx += w * x * x, syy += w * y * y, sxy += w * x * y;
        }
      }
    }
  }
  const double mx = sx / sum, my = sy / sum;
  return {
      {mx, my},
      sum,
      DiametersFromMoments(sxx / sum - mx * mx, syy / sum - my * my, sxy / sum - mx * my).minor};
}

// One camera of the club rig rendering a look; its background learnt from frames without the
// ball, then a frame with it.
class Scene {
 public:
  Scene(const sim::Look& look, int width = 640, int height = 360, int camera = 0,
        const sim::ClubRigOptions& rig = {}, double defocus = 0.0)
      : camera_(sim::ClubRig(3, width, height, false, rig).cameras[camera]) {
    sim::SceneOptions scene;
    scene.look = look;
    sim::RenderOptions render;
    render.static_supersampling = 2;
    render.defocus_px = defocus;
    renderer_.emplace(camera_, scene, render);
    BackgroundOptions options;
    background_ = BackgroundModel(width, height, options);
  }

  // Frames without the ball (players moving as in play) for the background to learn.
  void Learn(int frames, double t0 = 0.0) {
    for (int k = 0; k < frames; ++k)
      Render({}, t0 + k / 60.0, k), background_.Update(frame_.View());
  }
  // A frame with the ball over `samples` (centres over the exposure).
  void Render(const std::vector<Eigen::Vector3d>& samples, double t, uint64_t k) {
    sim::FrameContent content;
    content.t = t;
    content.ball = samples;
    content.players[0] =
        player_ ? *player_ : Eigen::Vector2d(-2.25 - 0.1 * std::sin(0.9 * t), -0.3);
    content.players[1] = {2.25 + 0.1 * std::sin(1.1 * t + 1.0), 0.3};
    renderer_->Render(content, k + 1000, &frame_);
  }
  // A cheap encoder's chroma: each chroma sample the mean of its 3x3 neighbours (the ball's
  // colour spread over its surroundings, as H.264 at a low rate does to a ball of 3-5 px).
  void SmearChroma() {
    const int w = frame_.chroma_width(), h = frame_.chroma_height();
    for (uint8_t* plane : {frame_.u(), frame_.v()}) {
      const std::vector<uint8_t> copy(plane, plane + static_cast<std::size_t>(w) * h);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          int sum = 0, n = 0;
          for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
              const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
              sum += copy[static_cast<std::size_t>(yy) * w + xx], ++n;
            }
          }
          plane[static_cast<std::size_t>(y) * w + x] = static_cast<uint8_t>((sum + n / 2) / n);
        }
      }
    }
  }
  // The region nearest the exact centre, whole-image search.
  std::optional<CoverageRegion> Find(const BallColour& ball, const Eigen::Vector2d& near,
                                     std::vector<CoverageRegion>* all = nullptr,
                                     const ForegroundOptions& options = {}) {
    std::vector<CoverageRegion> regions;
    finder_.Find(frame_.View(), background_, ball, {}, options, &regions);
    if (all) *all = regions;
    std::optional<CoverageRegion> best;
    for (const auto& r : regions) {
      if (!best || (Eigen::Vector2d(r.region.cx, r.region.cy) - near).norm() <
                       (Eigen::Vector2d(best->region.cx, best->region.cy) - near).norm()) {
        best = r;
      }
    }
    return best;
  }
  // A thin strip of `colour` from (x0, y0) to (x1, y1), `width` px across, painted over the
  // frame: an arm or a shirt's edge of the ball's colour, sharp (no blur).
  void PaintStrip(double x0, double y0, double x1, double y1, double width, const Yuv& colour) {
    const Eigen::Vector2d a(x0, y0), ab = Eigen::Vector2d(x1, y1) - a;
    const int w = frame_.width(), h = frame_.height();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const Eigen::Vector2d p(x, y);
        const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if ((p - a - s * ab).norm() > 0.5 * width) continue;
        frame_.y()[static_cast<std::size_t>(y) * w + x] = static_cast<uint8_t>(colour.y);
        const std::size_t c = static_cast<std::size_t>(y / 2) * frame_.chroma_width() + x / 2;
        frame_.u()[c] = static_cast<uint8_t>(colour.u);
        frame_.v()[c] = static_cast<uint8_t>(colour.v);
      }
    }
  }
  // Player A standing at `feet` (x, y) from now on; nullopt: swaying as in play.
  void PlacePlayer(const std::optional<Eigen::Vector2d>& feet) { player_ = feet; }
  const Camera& camera() const { return camera_; }
  BackgroundModel& background() { return background_; }
  const I420Image& frame() const { return frame_; }

 private:
  Camera camera_;
  std::optional<sim::CameraRenderer> renderer_;
  BackgroundModel background_;
  ForegroundFinder finder_;
  I420Image frame_;
  std::optional<Eigen::Vector2d> player_;
};

// Ball centres over an exposure of `exposure` s moving at `velocity` m/s through p.
std::vector<Eigen::Vector3d> Exposure(const Eigen::Vector3d& p, const Eigen::Vector3d& velocity,
                                      double exposure, int samples) {
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < samples; ++k) {
    out.push_back(p + velocity * exposure * ((k + 0.5) / samples - 0.5));
  }
  return out;
}

// The k-th of the 12 places over the table the measures are taken at.
Eigen::Vector3d Place(int k) { return {-1.0 + 0.18 * k, 0.5 * std::sin(k), 0.2 + 0.03 * (k % 5)}; }

struct Errors {
  Eigen::Vector2d centre{1e9, 1e9};  // measured - exact, px
  double diameter_px = 1e9;          // measured - exact (diameter of equal area)
  double streak_px = 0.0;
  int regions = 0;
  bool found = false;
};

Errors Measure(Scene& scene, const BallColour& ball, const std::vector<Eigen::Vector3d>& samples,
               double t = 1.0, uint64_t k = 999) {
  scene.Render(samples, t, k);
  const Silhouette exact = Exact(scene.camera(), samples);
  std::vector<CoverageRegion> all;
  const auto found = scene.Find(ball, exact.centre, &all);
  Errors e;
  e.regions = static_cast<int>(all.size());
  if (!found) return e;
  e.found = (Eigen::Vector2d(found->region.cx, found->region.cy) - exact.centre).norm() < 3.0;
  e.centre = Eigen::Vector2d(found->region.cx, found->region.cy) - exact.centre;
  e.diameter_px = found->region.diameter - 2.0 * std::sqrt(exact.area / M_PI);
  e.streak_px = found->streak_px;
  return e;
}

// Bias (mean error) and spread of the centre and diameter over ball positions across the table.
struct Bias {
  double centre = 0.0, diameter = 0.0, centre_rms = 0.0, diameter_rms = 0.0;
  int found = 0, tries = 0;
};

Bias BiasOver(Scene& scene, const BallColour& ball, const Eigen::Vector3d& velocity = {0, 0, 0},
              double exposure = 0.0) {
  Bias bias;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double dsum = 0.0, c2 = 0.0, d2 = 0.0;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Vector3d p = Place(k);
    const Errors e =
        Measure(scene, ball, Exposure(p, velocity, exposure, 24), 1.0 + k / 60.0, 999 + k);
    ++bias.tries;
    if (!e.found) continue;
    ++bias.found;
    sum += e.centre, dsum += e.diameter_px;
    c2 += e.centre.squaredNorm(), d2 += e.diameter_px * e.diameter_px;
  }
  if (bias.found == 0) return bias;
  bias.centre = (sum / bias.found).norm();
  bias.diameter = dsum / bias.found;
  bias.centre_rms = std::sqrt(c2 / bias.found);
  bias.diameter_rms = std::sqrt(d2 / bias.found);
  std::printf("mean error (%+.3f, %+.3f) ", sum.x() / bias.found, sum.y() / bias.found);
  std::printf("bias: centre %.3f px (rms %.3f), diameter %+.3f px (rms %.3f), found %d of %d\n",
              bias.centre, bias.centre_rms, bias.diameter, bias.diameter_rms, bias.found,
              bias.tries);
  return bias;
}

TEST(ForegroundScene, ASharpBallIsMeasuredToATenthOfAPixel) {
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const Bias bias = BiasOver(scene, BallColour::Orange());
  EXPECT_EQ(bias.found, bias.tries);
  EXPECT_LE(bias.centre, 0.1);
  EXPECT_LE(std::abs(bias.diameter), 0.1);
  EXPECT_LE(bias.centre_rms, 0.3);
}

TEST(ForegroundScene, TheBottomHalfOfTheBallInShadow) {
  // Lamps straight above: the ball's top is lit and its bottom dark. The coverage centre is the
  // ball's centre, not its lit half.
  Scene scene(sim::PresetLook("overhead"));
  scene.Learn(30);
  const Bias bias = BiasOver(scene, BallColour::Orange());
  EXPECT_EQ(bias.found, bias.tries);
  // The target is 0.1 px for both; measured 0.143 px and -0.281 px (2026-12-07): the darkest
  // edge of the ball over a dark table is still partly lost (README, "Measured on many worlds").
  EXPECT_LE(bias.centre, 0.15);
  EXPECT_LE(std::abs(bias.diameter), 0.3);
}

TEST(ForegroundScene, ATwentyPixelStreakAtASixtiethOfASecond) {
  // A webcam's exposure: 1/60 s of a ball at 9 m/s is a faint streak about 20 px long.
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const Eigen::Vector3d velocity(9.0, 0.0, 1.0);
  const double exposure = 1.0 / 60.0;
  const Bias bias = BiasOver(scene, BallColour::Orange(), velocity, exposure);
  EXPECT_EQ(bias.found, bias.tries);
  // Targets 0.1 px; measured 0.25 px and +0.54 px: both missed (README, "Measured on many
  // worlds"). A streak's pixels are each a small share of the ball; the blocks above min_alpha
  // are its middle, its faint ends are partly lost. (Before the renderer drew every subpixel cell
  // at every time sample, its streaks were dashed, and the dashes passed: 0.08 and +0.41 px.)
  EXPECT_LE(bias.centre, 0.3);
  EXPECT_LE(std::abs(bias.diameter), 0.6);
  // The streak's length says how fast the ball crossed the picture: the block regions hold only
  // pieces of it (the frame below: a piece 5 px off the middle); the search along the predicted
  // path (streak_search.h) finds it whole.
  const Eigen::Vector3d p(-0.3, 0.1, 0.3);
  const auto samples = Exposure(p, velocity, exposure, 48);
  scene.Render(samples, 2.0, 5000);
  const Silhouette exact = Exact(scene.camera(), samples);
  const auto a = scene.camera().Project(samples.front()),
             b = scene.camera().Project(samples.back());
  const double length = (*b - *a).norm() * 48.0 / 47.0;
  // Predicted 1 cm off, its motion over a frame of 1/30 s (the exposure is half of it).
  const Eigen::Vector3d guess = p + Eigen::Vector3d(0.01, 0.0, -0.005);
  const auto from = scene.camera().Project(guess - velocity / 60.0),
             to = scene.camera().Project(guess + velocity / 60.0),
             mid = scene.camera().Project(guess);
  const double diameter =
      2.0 * table::kBallRadius * scene.camera().fx / (scene.camera().cam_from_world * p).z();
  StreakSearch search;
  const auto hit = search.Find(scene.frame().View(), scene.background(), BallColour::Orange(),
                               mid->x(), mid->y(), to->x() - from->x(), to->y() - from->y(),
                               (*to - *from).norm(), diameter, {});
  ASSERT_TRUE(hit.has_value());
  const double off = std::hypot(hit->cx - exact.centre.x(), hit->cy - exact.centre.y());
  std::printf("streak %.1f px, found %.1f px long, %.2f px off\n", length, hit->length_px, off);
  EXPECT_GT(length, 15.0);
  EXPECT_NEAR(hit->length_px, length, 0.25 * length);
  EXPECT_LE(off, 1.0);
}

TEST(ForegroundScene, ASmallStreakWhoseChromaTheEncoderSmearedIsStillTheBall) {
  // A webcam: a ball of about 5 px blurred over 1/60 s, its chroma spread by the encoder. The
  // colour tables, which tell skin and shirts from the ball in a round region's core, see
  // little of the ball's colour in it: they must not judge a core whose blocks' colour is
  // mostly the background's, and so must find the ball almost wherever it is found without them.
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const ColorLut lut = DefaultOrangeBall().BuildLut();
  ForegroundOptions with_tables;
  with_tables.lut = &lut;
  with_tables.lut_mask = DefaultOrangeBall().MaskOf("ball");
  const auto near = [](const std::optional<CoverageRegion>& r, const Eigen::Vector2d& centre) {
    return r && (Eigen::Vector2d(r->region.cx, r->region.cy) - centre).norm() < 2.0;
  };
  int found = 0, found_without_tables = 0;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Vector3d p = Place(k);
    const auto samples = Exposure(p, {4.0, 0.0, 1.0}, 1.0 / 60.0, 24);
    scene.Render(samples, 1.0 + k / 60.0, 6000 + k);
    scene.SmearChroma();
    const Silhouette exact = Exact(scene.camera(), samples);
    found +=
        near(scene.Find(BallColour::Orange(), exact.centre, nullptr, with_tables), exact.centre);
    found_without_tables += near(scene.Find(BallColour::Orange(), exact.centre), exact.centre);
  }
  std::printf("small smeared streak found in %d of 12 frames (%d without the tables)\n", found,
              found_without_tables);
  // Measured: 6 of 12 with the tables, 8 without (judging every covered pixel: 3 of 12; with the
  // renderer's dashed streaks of before 8 and 9).
  EXPECT_GE(found_without_tables, 7);
  EXPECT_GE(found, found_without_tables - 2);
}

TEST(ForegroundScene, ABallOfThreePixels) {
  Scene scene(sim::ClubLook(), 320, 180);
  scene.Learn(30);
  const Bias bias = BiasOver(scene, BallColour::Orange());
  EXPECT_GE(bias.found, bias.tries - 1);
  EXPECT_LE(bias.centre, 0.2);
  EXPECT_LE(bias.centre_rms, 0.5);
}

TEST(ForegroundScene, AWhiteBallBesideAWhiteLineWithLampsAndLettering) {
  Scene scene(sim::PresetLook("white"));
  scene.Learn(30);
  // Along the near edge line, 3 cm above it.
  double worst = 0.0;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d p(-1.2 + 0.45 * k, -table::kHalfWidth + 0.01, 0.035);
    const Errors e = Measure(scene, BallColour::White(), {p}, 1.0 + k / 60.0, 700 + k);
    ASSERT_TRUE(e.found) << k;
    worst = std::max(worst, e.centre.norm());
  }
  EXPECT_LE(worst, 0.5);
}

TEST(ForegroundScene, StaticLampsBannersLogosAndASpareBallAreBackground) {
  for (const char* name : {"white", "banner", "broadcast"}) {
    sim::Look look = sim::PresetLook(name);
    look.spare_ball = Eigen::Vector3d(2.0, -1.2, table::kFloorZ + table::kBallRadius);
    look.arm_swing = 0.0;
    Scene scene(look);
    scene.Learn(40);
    // The players keep still: nothing in the picture is new.
    std::vector<CoverageRegion> regions;
    scene.Render({}, 0.0, 3000);
    scene.Find(look.white_ball() ? BallColour::White() : BallColour::Orange(), {0, 0}, &regions);
    EXPECT_TRUE(regions.empty()) << name << ": " << regions.size() << " region(s), first at "
                                 << (regions.empty() ? 0 : regions[0].region.cx) << ", "
                                 << (regions.empty() ? 0 : regions[0].region.cy);
  }
}

TEST(ForegroundScene, ABallColouredShirtAndArmMovingFast) {
  sim::Look look = sim::PresetLook("banner");  // orange shirt and shoes, arms swinging
  Scene scene(look, 640, 360, 1);
  scene.Learn(30);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d p(-0.8 + 0.3 * k, 0.2, 0.3);
    const Errors e = Measure(scene, BallColour::Orange(), {p}, 1.0 + k / 60.0, 800 + k);
    ASSERT_TRUE(e.found) << k;
    EXPECT_LE(e.centre.norm(), 0.35) << k;
  }
}

TEST(ForegroundScene, ABallHeldStillIsNotAbsorbedAtOnce) {
  // A serve: the ball rests in the hand for a second before the toss.
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const Eigen::Vector3d p(-1.5, 0.3, 0.1);
  double first = 0.0, last = 0.0;
  for (int k = 0; k < 60; ++k) {
    scene.Render({p}, 1.0, 4000 + k);
    std::vector<CoverageRegion> all;
    const Silhouette exact = Exact(scene.camera(), {p});
    const auto found = scene.Find(BallColour::Orange(), exact.centre, &all);
    const double coverage = found ? found->coverage / exact.area : 0.0;
    if (k == 0) first = coverage;
    last = coverage;
    // As the tracker does: the window around the ball it follows is kept out of the learning.
    scene.background().Update(scene.frame().View(),
                              Roi::Around(exact.centre.x(), exact.centre.y(), 40, 40, 640, 360));
  }
  std::printf("coverage of a still ball: %.2f at first, %.2f after a second\n", first, last);
  EXPECT_GT(first, 0.9);
  EXPECT_GT(last, 0.7);
}

// The pixel nearest the middle of what `stood` alone covers (it differs from `now` by 40 levels
// where `elsewhere` does not) whose 15x15 neighbourhood it all covers; nullopt if none.
std::optional<Eigen::Vector2d> InsideWhatOnlyItCovered(const I420Image& stood,
                                                       const I420Image& elsewhere,
                                                       const I420Image& now) {
  const int w = stood.width(), h = stood.height();
  std::vector<uint8_t> mask(static_cast<std::size_t>(w) * h, 0);
  double sx = 0.0, sy = 0.0;
  int covered = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const int seen = now.y()[i];
      if (std::abs(stood.y()[i] - seen) > 40 && std::abs(elsewhere.y()[i] - seen) < 10) {
        mask[i] = 1, sx += x, sy += y, ++covered;
      }
    }
  }
  if (covered < 400) return std::nullopt;
  const Eigen::Vector2d middle(sx / covered, sy / covered);
  std::optional<Eigen::Vector2d> inside;
  for (int y = 7; y < h - 7; ++y) {
    for (int x = 7; x < w - 7; ++x) {
      bool all = true;
      for (int dy = -7; dy <= 7 && all; ++dy) {
        for (int dx = -7; dx <= 7 && all; ++dx) {
          all = mask[static_cast<std::size_t>(y + dy) * w + x + dx] != 0;
        }
      }
      const Eigen::Vector2d q(x, y);
      if (all && (!inside || (q - middle).norm() < (*inside - middle).norm())) inside = q;
    }
  }
  return inside;
}

TEST(ForegroundScene, APlayerWhoStoodStillAndLeftLeavesNoGhost) {
  // A white ball tossed where a player had stood still for two seconds (a serve's stance), the
  // player gone. The short-term model learnt the player; the hall behind them differs from it by
  // a torso's area, which the ball joined and was lost in: the long-term model is taken back.
  Scene scene(sim::PresetLook("white"), 640, 360, 1);
  BackgroundOptions with_long_term;
  with_long_term.long_term = true;
  scene.background() = BackgroundModel(640, 360, with_long_term);
  const Eigen::Vector2d stance(-2.25, -0.3), away(-2.25, -1.6);
  scene.PlacePlayer(away);
  scene.Learn(60);
  scene.PlacePlayer(stance);
  for (int k = 0; k < 120; ++k) {
    scene.Render({}, 1.0 + k / 60.0, 100 + k);
    scene.background().Update(scene.frame().View());
  }
  // The ball before the middle of what the player covered, at 70 % of their depth (what
  // differs from the frame with the player away and not between two places away).
  const I420Image stood = scene.frame();
  scene.PlacePlayer(Eigen::Vector2d(-2.25, 1.6));
  scene.Render({}, 3.0, 300);
  const I420Image elsewhere = scene.frame();
  scene.PlacePlayer(away);
  scene.Render({}, 3.0, 300);
  const std::optional<Eigen::Vector2d> inside =
      InsideWhatOnlyItCovered(stood, elsewhere, scene.frame());
  ASSERT_TRUE(inside.has_value()) << "the player covered no hall in this camera";
  const Camera& camera = scene.camera();
  const double depth = (camera.cam_from_world * Eigen::Vector3d(stance.x(), stance.y(), 0.3)).z();
  const Eigen::Vector2d n = camera.NormalizedFromPixel(*inside);
  const Eigen::Vector3d p =
      camera.cam_from_world.Inverse() * (0.7 * depth * Eigen::Vector3d(n.x(), n.y(), 1.0));
  int found = 0;
  double worst = 0.0;
  for (int k = 0; k < 24; ++k) {
    const Eigen::Vector3d q = p + Eigen::Vector3d(0.0, 0.0, 0.002 * k);  // rising slowly
    const Errors e = Measure(scene, BallColour::White(), {q}, 3.0 + k / 60.0, 400 + k);
    found += e.found;
    // Measured on the hall once every block row has been visited (row_stride frames).
    if (e.found && k >= scene.background().options().row_stride) {
      worst = std::max(worst, e.centre.norm());
    }
    scene.background().Update(scene.frame().View());
  }
  std::printf(
      "ball before the stance's hall: found in %d of 24 frames, worst centre %.2f px "
      "after the first %d\n",
      found, worst, scene.background().options().row_stride);
  EXPECT_EQ(found, 24);
  EXPECT_LE(worst, 0.5);
}

TEST(BackgroundOptions, ValidatesItsRatesAndSettling) {
  std::string why;
  EXPECT_TRUE(BackgroundOptions{}.IsValid(&why)) << why;
  BackgroundOptions o;
  o.settle_frames = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("settling"), std::string::npos) << why;
  o = {};
  o.still_learn_rate = 0.5;  // faster than what looks like the background
  EXPECT_FALSE(o.IsValid(&why));
}
}  // namespace
}  // namespace p4::segment

namespace p4::segment {
namespace {

// The share of a frame's pixels (a 4-pixel grid) that a colour-class set takes.
double TakenShare(const I420Image& frame, const ColorClassSet& classes) {
  const ColorLut lut = classes.BuildLut();
  const uint32_t mask = classes.MaskOf("ball");
  int taken = 0, all = 0;
  for (int y = 0; y < frame.height(); y += 2) {
    for (int x = 0; x < frame.width(); x += 2) {
      const uint8_t yy = frame.y()[y * frame.width() + x];
      const uint8_t u = frame.u()[(y / 2) * frame.chroma_width() + x / 2];
      const uint8_t v = frame.v()[(y / 2) * frame.chroma_width() + x / 2];
      taken += (lut.Classify(yy, u, v) & mask) != 0;
      ++all;
    }
  }
  return static_cast<double>(taken) / all;
}

// --ball auto's learning (colour_learning.h) from a few frames: a yellow ball over a wood floor
// whose colour the default yellow classes take too. Eight views of the ball's core, where it
// differs from the learnt background, give classes that take the ball in new frames and almost
// nothing of the hall.
TEST(ForegroundScene, ColoursLearnedFromAFewFrames) {
  sim::Look look = sim::ClubLook();
  look.ball = sim::BallColour("yellow");
  look.floor = {0.57f, 0.22f, 0.12f};  // wood, near the yellow's shaded side
  look.light = Eigen::Vector3d(0.1, 0.1, 1.0).normalized();
  look.ball_ambient = 0.5;  // lamps above: a bright top and a dark bottom
  Scene scene(look, 1280, 720);
  scene.Learn(40);
  ColourLearningOptions learning;
  learning.min_samples = 40;  // a ball of 8-10 px: its core is a dozen pixels a view
  const auto ball_at = [](int k) {
    return Eigen::Vector3d(-1.1 + 0.27 * k, 0.4 * std::cos(k), 0.15 + 0.04 * (k % 4));
  };
  ColourSamples samples;
  for (int k = 0; k < 8; ++k) {
    const std::vector<Eigen::Vector3d> at = {ball_at(k)};
    scene.Render(at, 1.0 + k / 60.0, 900 + k);
    const Silhouette exact = Exact(scene.camera(), at);
    samples.AddDisc(scene.frame().View(), exact.centre, 2.0 * std::sqrt(exact.area / M_PI),
                    learning, &scene.background());
  }
  LearnedColour learnt;
  std::string why;
  ASSERT_TRUE(samples.Learn(learning, &learnt, &why)) << why;
  // The lit colour is a yellow: U well below neutral, V a little above it.
  EXPECT_LT(learnt.ball.lit.u, 100.0f);
  EXPECT_GT(learnt.ball.lit.v, 130.0f);
  // Of a frame without the ball, the learnt classes take almost nothing; the default yellow
  // classes take the floor.
  scene.Render({}, 2.0, 950);
  const double learnt_share = TakenShare(scene.frame(), learnt.classes);
  const double default_share = TakenShare(scene.frame(), DefaultYellowBall());
  std::printf("hall taken: learnt %.4f, default yellow %.4f\n", learnt_share, default_share);
  EXPECT_LT(learnt_share, 0.002);
  EXPECT_GT(default_share, 5.0 * learnt_share);
  // New frames: the learnt classes find the ball where it is (its colour region's centre within
  // 2 px of the exact one, however it is shaded) in 6 of 6 places.
  const ColorLut lut = learnt.classes.BuildLut();
  SegmentOptions options;
  options.mask = learnt.classes.MaskOf("ball");
  BlobFinder finder;
  std::vector<Region> regions;
  int found = 0;
  for (int k = 0; k < 6; ++k) {
    const std::vector<Eigen::Vector3d> at = {ball_at(k) + Eigen::Vector3d(0.11, -0.2, 0.05)};
    scene.Render(at, 3.0 + k / 60.0, 960 + k);
    const Silhouette exact = Exact(scene.camera(), at);
    finder.Find(scene.frame().View(), lut, {}, options, &regions);
    for (const Region& r : regions) {
      if ((Eigen::Vector2d(r.cx, r.cy) - exact.centre).norm() < 2.0) {
        ++found;
        break;
      }
    }
  }
  EXPECT_EQ(found, 6);
}

// The centre from the ball's edge (ball_edge.h), started from the colour tables' region (the
// paper's centroid), against the exact projection: bias and spread over positions on the table.
struct EdgeErrors {
  double bias = 0.0, rms = 0.0, region_rms = 0.0;
  int measured = 0, tries = 0;
};

EdgeErrors EdgeOver(Scene& scene, const Eigen::Vector3d& velocity, double exposure,
                    bool smear_chroma = false) {
  const ColorLut lut = DefaultOrangeBall().BuildLut();
  SegmentOptions segment;
  segment.mask = DefaultOrangeBall().MaskOf("ball");
  BlobFinder blobs;
  EdgeErrors out;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double e2 = 0.0, r2 = 0.0;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Vector3d p = Place(k);
    const auto samples = Exposure(p, velocity, exposure, 24);
    scene.Render(samples, 1.0 + k / 60.0, 7000 + k);
    if (smear_chroma) scene.SmearChroma();
    const Silhouette exact = Exact(scene.camera(), samples);
    std::vector<Region> regions;
    blobs.Find(scene.frame().View(), lut, {}, segment, &regions);
    const Region* region = nullptr;
    for (const Region& r : regions) {
      if ((Eigen::Vector2d(r.cx, r.cy) - exact.centre).norm() < 3.0) region = &r;
    }
    ++out.tries;
    if (!region) continue;
    const auto e = MeasureEdgeCentre(scene.frame().View(), region->cx, region->cy,
                                     0.5 * region->major_diameter + 0.5);
    if (!e) continue;
    ++out.measured;
    const Eigen::Vector2d error = Eigen::Vector2d(e->cx, e->cy) - exact.centre;
    sum += error, e2 += error.squaredNorm();
    r2 += (Eigen::Vector2d(region->cx, region->cy) - exact.centre).squaredNorm();
  }
  if (out.measured == 0) return out;
  out.bias = (sum / out.measured).norm();
  out.rms = std::sqrt(e2 / out.measured);
  out.region_rms = std::sqrt(r2 / out.measured);
  std::printf(
      "edge centre: bias %.3f px, rms %.3f px (the region's centroid: rms %.3f px), %d of "
      "%d measured\n",
      out.bias, out.rms, out.region_rms, out.measured, out.tries);
  return out;
}

TEST(BallEdge, TheCentreOfASharpBallFromItsEdge) {
  Scene scene(sim::ClubLook());
  const EdgeErrors e = EdgeOver(scene, {0, 0, 0}, 0.0);
  EXPECT_GE(e.measured, 11);
  EXPECT_LE(e.bias, 0.1);
  EXPECT_LE(e.rms, 0.2);
}

TEST(BallEdge, TheBottomHalfInShadow) {
  // Lamps straight above and a dark table: the ball's dark bottom is close to the table's luma
  // and colour, and its edge there is lost too. Measured: bias 0.93 px, rms 1.13 px against the
  // region's 1.33 px (2026-12-07; the 0.1 px target is not met: README, "Measured on many
  // worlds").
  Scene scene(sim::PresetLook("overhead"));
  const EdgeErrors e = EdgeOver(scene, {0, 0, 0}, 0.0);
  EXPECT_GE(e.measured, 10);
  EXPECT_LT(e.rms, e.region_rms);
}

TEST(BallEdge, AStreakIsCentredAtMidExposure) {
  // 1/300 s at 9 m/s: a streak of 3 cm, as in a hall's 2-4 ms exposures.
  Scene scene(sim::ClubLook());
  const EdgeErrors e = EdgeOver(scene, {9.0, 0.0, 1.0}, 1.0 / 300.0);
  EXPECT_GE(e.measured, 10);
  EXPECT_LE(e.bias, 0.15);
  EXPECT_LE(e.rms, 0.25);
  EXPECT_LT(e.rms, e.region_rms);
}

TEST(BallEdge, ChromaTheEncoderSmearedDoesNotMoveTheCentre) {
  // The tables take the part of the ball whose chroma is right; the edge is mostly in the luma.
  Scene scene(sim::ClubLook());
  const EdgeErrors e = EdgeOver(scene, {2.0, 0.0, 0.5}, 1.0 / 500.0, true);
  EXPECT_GE(e.measured, 8);  // measured: 9 of 12
  EXPECT_LE(e.rms, 0.2);
  EXPECT_LT(e.rms, 0.5 * e.region_rms);
}

// A webcam's frame: 1/30 s of a ball at 12 m/s at 640x360 is a streak of about 60 px in which the
// ball is under a tenth of each pixel (a few levels): too faint for any per-block threshold, found
// along the path the filter predicts.
// The filter's prediction of a ball at p flying at `velocity`: 2 cm off, its motion over a
// whole frame period of `frame` s. Returns its image path (end minus start), px.
Eigen::Vector2d PredictedPath(const Scene& scene, const Eigen::Vector3d& p,
                              const Eigen::Vector3d& velocity, double frame,
                              Eigen::Vector2d* middle = nullptr) {
  const Eigen::Vector3d guess = p + Eigen::Vector3d(0.015, -0.01, 0.01);
  const auto a = scene.camera().Project(guess - 0.5 * frame * velocity);
  const auto b = scene.camera().Project(guess + 0.5 * frame * velocity);
  const auto m = scene.camera().Project(guess);
  EXPECT_TRUE(a && b && m);
  if (!a || !b || !m) return Eigen::Vector2d::Zero();
  if (middle) *middle = *m;
  return *b - *a;
}

// The streak search along that prediction, for an orange ball of its size at p.
std::optional<StreakHit> SearchPredicted(Scene& scene, const Eigen::Vector3d& p,
                                         const Eigen::Vector3d& velocity, double frame,
                                         const StreakSearchOptions& options, StreakSearch* search) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  const Eigen::Vector2d d = PredictedPath(scene, p, velocity, frame, &m);
  const double diameter =
      2.0 * table::kBallRadius * scene.camera().fx / (scene.camera().cam_from_world * p).z();
  return search->Find(scene.frame().View(), scene.background(), BallColour::Orange(), m.x(), m.y(),
                      d.x(), d.y(), d.norm(), diameter, options);
}

TEST(StreakSearchScene, AFaintStreakAlongThePredictedPath) {
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const Eigen::Vector3d velocity(12.0, -1.0, 1.5);
  const double exposure = 1.0 / 30.0, frame = 1.0 / 25.0;
  ForegroundFinder finder;
  StreakSearch search;
  StreakSearchOptions options;
  int found = 0, by_blocks = 0, within = 0;
  double sum_length_ratio = 0.0;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Vector3d p = Place(k);
    const auto samples = Exposure(p, velocity, exposure, 64);
    scene.Render(samples, 1.0 + k / 60.0, 999 + k);
    const Silhouette exact = Exact(scene.camera(), samples);
    const auto hit = SearchPredicted(scene, p, velocity, frame, options, &search);
    const Eigen::Vector2d d = PredictedPath(scene, p, velocity, frame);
    std::vector<CoverageRegion> regions;
    finder.Find(scene.frame().View(), scene.background(), BallColour::Orange(), {}, {}, &regions);
    by_blocks += std::any_of(regions.begin(), regions.end(), [&](const CoverageRegion& r) {
      return std::hypot(r.region.cx - exact.centre.x(), r.region.cy - exact.centre.y()) < 3.0;
    });
    if (!hit) continue;
    const double error = std::hypot(hit->cx - exact.centre.x(), hit->cy - exact.centre.y());
    const double length = d.norm() * exposure / frame;
    std::printf("streak %.1f px (found %.1f), share %.3f (expected %.3f), snr %.1f, off %.2f px\n",
                length, hit->length_px, hit->share, hit->expected_share, hit->snr, error);
    ++found;
    within += error <= 1.5;
    sum_length_ratio += hit->length_px / length;
  }
  std::printf("faint streaks found in %d of 12 (by blocks: %d), %d within 1.5 px\n", found,
              by_blocks, within);
  EXPECT_GE(found, 11);
  // Measured 10 of 12 within 0.75 px, the others 1.6 and 2.5 px off.
  EXPECT_GE(within, 10);
  ASSERT_GT(found, 0);
  EXPECT_NEAR(sum_length_ratio / found, 1.0, 0.3);  // the exposure's share of the frame
}

TEST(StreakSearchScene, SkinBrighteningABrownFloorDoesNotShowTheBallsColour) {
  // Webcam tuning 18: a hand over a brown floor moved as a faint streak would, in two cameras for
  // three frames, and started a track 6 m off. Its summed difference from the floor (lighter,
  // little change of chroma) unmixes as no share of the orange ball at any shading; the ball's
  // own streak does, its chroma smeared as a cheap encoder smears it (the sum is kept).
  const Eigen::Vector3d velocity(12.0, -1.0, 1.5);
  const double exposure = 1.0 / 30.0, frame = 1.0 / 25.0;
  for (const bool skin : {false, true}) {
    sim::Look look = sim::ClubLook();
    look.table = {0.49f, 0.35f, 0.2f};  // the floor of that scene
    if (skin) look.ball = look.skin;
    Scene scene(look);
    scene.Learn(30);
    StreakSearch search;
    int found = 0;
    double lowest = 1e9, highest = -1e9;
    for (int k = 0; k < 12; ++k) {
      const Eigen::Vector3d p = Place(k);
      scene.Render(Exposure(p, velocity, exposure, 64), 1.0 + k / 60.0, 999 + k);
      scene.SmearChroma();
      const auto hit = SearchPredicted(scene, p, velocity, frame, {}, &search);
      if (!hit) continue;
      ++found;
      lowest = std::min(lowest, hit->colour_residual);
      highest = std::max(highest, hit->colour_residual);
    }
    std::printf("%s streaks found in %d of 12, colour residual %.2f-%.2f\n",
                skin ? "skin" : "orange", found, lowest, highest);
    // Measured: the orange streaks found in 12 of 12, residuals 0.01-0.18; the skin's in 5 of 12
    // (it passes the search's share and ring tests less often), residuals 1.00 (no positive
    // share of the ball fits).
    EXPECT_GE(found, skin ? 4 : 11);
    if (skin) {
      EXPECT_GE(lowest, 0.9) << skin;  // track::FrameSetOptions::off_colour_residual
    } else {
      EXPECT_LT(highest, 0.5);
    }
  }
}

TEST(StreakSearchScene, NothingWhereThereIsNoBall) {
  // The same predictions over frames without the ball: the picture's clutter (players, lines,
  // noise) must not pass for a streak.
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const Eigen::Vector3d velocity(12.0, -1.0, 1.5);
  StreakSearch search;
  int found = 0;
  for (int k = 0; k < 12; ++k) {
    scene.Render({}, 1.0 + k / 60.0, 999 + k);
    const Eigen::Vector3d p = Place(k);
    const auto a = scene.camera().Project(p - 0.02 * velocity);
    const auto b = scene.camera().Project(p + 0.02 * velocity);
    const auto m = scene.camera().Project(p);
    const Eigen::Vector2d d = *b - *a;
    const double diameter =
        2.0 * table::kBallRadius * scene.camera().fx / (scene.camera().cam_from_world * p).z();
    found += search
                 .Find(scene.frame().View(), scene.background(), BallColour::Orange(), m->x(),
                       m->y(), d.x(), d.y(), d.norm(), diameter, {})
                 .has_value();
  }
  EXPECT_EQ(found, 0);
}

// The whole-image finder's candidates, each measured by the streak search (FindStreaks, as the
// tracker and the sync's candidates take them): the hits.
std::vector<StreakHit> StreaksAnywhere(Scene& scene, StreakFinder& finder, double diameter) {
  StreakSearch search;
  std::vector<FoundStreak> found;
  FindStreaks(scene.frame().View(), scene.background(), BallColour::Orange(), diameter, {}, {},
              &finder, &search, &found);
  std::vector<StreakHit> hits;
  for (const FoundStreak& f : found) {
    EXPECT_GT(f.diameter_px, 0.0);
    hits.push_back(f.hit);
  }
  return hits;
}

// The ball's size over the table's middle, a little above it (what the tracker takes when it has
// no track), px.
double TableMiddleDiameter(const Scene& scene) {
  return 2.0 * table::kBallRadius * scene.camera().fx /
         (scene.camera().cam_from_world * Eigen::Vector3d(0.0, 0.0, 0.2)).z();
}

// The streaks of the tests below: 12 m/s across the table, a webcam's 1/30 s.
const Eigen::Vector3d kStreakVelocity(12.0, -1.0, 1.5);
constexpr double kStreakExposure = 1.0 / 30.0;

TEST(StreakFinderScene, AFaintStreakAnywhereWithNoPrediction) {
  // The streaks of the test above (50 px, each pixel under a tenth ball), with no track to say
  // where: the ball's size is taken over the table's middle, as the tracker does.
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const double diameter = TableMiddleDiameter(scene);
  int found = 0, within = 0;
  StreakFinder finder;  // one per camera, frame after frame
  for (int k = 0; k < 12; ++k) {
    const auto samples = Exposure(Place(k), kStreakVelocity, kStreakExposure, 64);
    scene.Render(samples, 1.0 + k / 60.0, 999 + k);
    const Silhouette exact = Exact(scene.camera(), samples);
    double best = 1e9;
    for (const StreakHit& h : StreaksAnywhere(scene, finder, diameter)) {
      best = std::min(best, std::hypot(h.cx - exact.centre.x(), h.cy - exact.centre.y()));
    }
    std::printf("frame %d: nearest hit %.2f px from the exact centre\n", k, best);
    found += best < 4.0;
    within += best <= 1.5;
  }
  std::printf("faint streaks found anywhere in %d of 12, %d within 1.5 px\n", found, within);
  EXPECT_GE(found, 10);
  EXPECT_GE(within, 8);
}

TEST(StreakFinderScene, ArmsOfTheBallsColourDoNotCrowdOutTheBall) {
  // The faint streaks above, and in every frame six sharp strips of the ball's lit colour (arms,
  // shirts' edges: 24 px long, 3 px wide), each at a new place: every strip outscores the faint
  // ball. The finder keeps enough candidates for the ball to stay among them (with 4, as
  // before, the strips took every place: the ball was found in none of the 12 frames).
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const double diameter = TableMiddleDiameter(scene);
  const Yuv arm = BallColour::Orange().Shaded(0.9f);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(40.0, 600.0), y(40.0, 320.0), angle(0.0, M_PI);
  int found = 0, outscored = 0;
  StreakFinder finder;
  for (int k = 0; k < 12; ++k) {
    const auto samples = Exposure(Place(k), kStreakVelocity, kStreakExposure, 64);
    scene.Render(samples, 1.0 + k / 60.0, 999 + k);
    const Silhouette exact = Exact(scene.camera(), samples);
    for (int strips = 0; strips < 6;) {
      const Eigen::Vector2d m(x(random), y(random));
      if ((m - exact.centre).norm() < 60.0) continue;  // not over the ball's streak
      const double a = angle(random);
      const Eigen::Vector2d along = 12.0 * Eigen::Vector2d(std::cos(a), std::sin(a));
      scene.PaintStrip(m.x() - along.x(), m.y() - along.y(), m.x() + along.x(), m.y() + along.y(),
                       3.0, arm);
      ++strips;
    }
    std::vector<StreakCandidate> candidates;
    StreakFinder probe = finder;  // the same state, its candidates looked at
    probe.Find(scene.frame().View(), scene.background(), BallColour::Orange(), {}, &candidates);
    const auto ball = std::find_if(candidates.begin(), candidates.end(), [&](const auto& c) {
      return std::hypot(c.cx - exact.centre.x(), c.cy - exact.centre.y()) < 6.0;
    });
    outscored += ball != candidates.end() && ball - candidates.begin() >= 4;
    double best = 1e9;
    for (const StreakHit& h : StreaksAnywhere(scene, finder, diameter)) {
      best = std::min(best, std::hypot(h.cx - exact.centre.x(), h.cy - exact.centre.y()));
    }
    found += best < 4.0;
  }
  std::printf(
      "beside 6 strips a frame: the ball found in %d of 12, behind 4 or more strips in %d\n", found,
      outscored);
  EXPECT_GE(outscored, 6);  // the strips do outscore the ball (measured: 6)
  EXPECT_GE(found, 9);      // measured: 10 (without the strips: 12)
}

TEST(StreakFinderScene, WhatPassesWithoutABallIsShortAndRare) {
  // Frames without the ball. One view alone cannot tell every thing of the ball's colour from a
  // ball (the tracker then asks for agreeing views, the ball's size and a flight): this hall's
  // players show short strips that unmix as the ball (shares 0.3-0.7 over 12-30 px, in the
  // plane of its colours). Measured: 10 in 12 frames, none longer than 30 px, none in two frames
  // in a row at one place (the ball's streaks of the test above are 45-65 px).
  Scene scene(sim::ClubLook());
  scene.Learn(30);
  const double diameter = TableMiddleDiameter(scene);
  int found = 0;
  double longest = 0.0;
  StreakFinder finder;
  for (int k = 0; k < 12; ++k) {
    scene.Render({}, 1.0 + k / 60.0, 999 + k);
    for (const StreakHit& h : StreaksAnywhere(scene, finder, diameter)) {
      ++found;
      longest = std::max(longest, h.length_px);
    }
  }
  std::printf("without a ball: %d hits in 12 frames, the longest %.1f px\n", found, longest);
  EXPECT_LE(found, 12);
  EXPECT_LT(longest, 35.0);
}

TEST(StreakFinderScene, ValidatesItsOptions) {
  StreakFinderOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.half_cells = {0};
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.cell_blocks = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("streak finder"), std::string::npos);
}

// The ball's width from its edges (EdgeCentre::minor_diameter) and from the moments of the luma's
// coverage (MeasureBall, what the tracker took before), each against the exact width, on 12
// places: the mean ratio, and how many were measured.
struct WidthRatios {
  double edge = 0.0, moments = 0.0;
  int measured = 0;
};

WidthRatios WidthsOver(Scene& scene, const Eigen::Vector3d& velocity, double exposure) {
  const ColorLut lut = DefaultOrangeBall().BuildLut();
  SegmentOptions segment;
  segment.mask = DefaultOrangeBall().MaskOf("ball");
  BlobFinder blobs;
  WidthRatios out;
  for (int k = 0; k < 12; ++k) {
    const auto samples = Exposure(Place(k), velocity, exposure, 24);
    scene.Render(samples, 1.0 + k / 60.0, 7000 + k);
    const Silhouette exact = Exact(scene.camera(), samples);
    const double truth = exact.minor_diameter;
    std::vector<Region> regions;
    blobs.Find(scene.frame().View(), lut, {}, segment, &regions);
    const Region* region = nullptr;
    for (const Region& r : regions) {
      if ((Eigen::Vector2d(r.cx, r.cy) - exact.centre).norm() < 3.0) region = &r;
    }
    if (!region) continue;
    const auto m = MeasureBall(scene.frame().View(), *region);
    const auto e = MeasureEdgeCentre(scene.frame().View(), region->cx, region->cy,
                                     0.5 * region->major_diameter + 0.5);
    if (!m || !e || !(e->minor_diameter > 0.0)) continue;
    ++out.measured;
    out.edge += e->minor_diameter / truth;
    // As the tracker did: the point-spread of 0.35 px taken out of the moments.
    out.moments +=
        std::sqrt(std::max(1.0, m->minor_diameter * m->minor_diameter - 16 * 0.1225)) / truth;
  }
  if (out.measured > 0) out.edge /= out.measured, out.moments /= out.measured;
  std::printf("width / exact: edges %.3f, moments %.3f, %d measured\n", out.edge, out.moments,
              out.measured);
  return out;
}

TEST(BallEdge, TheWidthOfASharpBallFromItsEdges) {
  // Measured 0.993 (the moments 0.983) at 1280x720, a ball of 10.5 px.
  Scene scene(sim::ClubLook(), 1280, 720);
  const WidthRatios w = WidthsOver(scene, {0, 0, 0}, 0.0);
  EXPECT_GE(w.measured, 10);
  EXPECT_NEAR(w.edge, 1.0, 0.015);
}

TEST(BallEdge, TheWidthOfABallWhoseBottomHalfIsInShadow) {
  // Lamps straight above: the luma's coverage holds the lit half only (its moments' width 0.50
  // of the ball's); the edges find the dark half's edge too (1.00). Where the colour region is
  // the lit half alone the rays may not reach the dark edge: measured in 5 of 12.
  Scene scene(sim::PresetLook("overhead"), 1280, 720);
  const WidthRatios w = WidthsOver(scene, {0, 0, 0}, 0.0);
  EXPECT_GE(w.measured, 4);
  EXPECT_NEAR(w.edge, 1.0, 0.03);
  EXPECT_LT(w.moments, 0.7);
}

TEST(BallEdge, AStreaksEdgesAreDrawnInByItsThinnerEnds) {
  // 1/300 s at 9 m/s (0.75 diameters of blur): across the motion a streak is covered less
  // towards its sides, and the half-level edge lies inside the ball's width (measured 0.94);
  // the tracker takes the edges' width only for rounder shapes (edge_diameter_max_elongation).
  Scene scene(sim::ClubLook(), 1280, 720);
  const WidthRatios w = WidthsOver(scene, {9.0, 0.0, 1.0}, 1.0 / 300.0);
  EXPECT_GE(w.measured, 10);
  EXPECT_GT(w.edge, 0.88);
  EXPECT_LT(w.edge, 0.98);
}

}  // namespace
}  // namespace p4::segment
