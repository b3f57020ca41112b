// Google Benchmark micro-benchmarks of each stage of the tracking loop (built with the `bench`
// preset: cmake --preset bench && cmake --build --preset bench &&
// build/bench/bench/p4_micro_bench). `p4track bench` gives the whole loop and the comparison with
// OpenCV; these isolate one stage.
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include "p4/geometry/epipolar.h"
#include "p4/geometry/triangulation.h"
#include "p4/segment/background_model.h"
#include "p4/segment/blob_finder.h"
#include "p4/segment/color_classes.h"
#include "p4/segment/foreground_finder.h"
#include "p4/segment/streak_finder.h"
#include "p4/segment/streak_search.h"
#include "p4/sim/camera_layout.h"
#include "p4/sim/renderer.h"
#include "p4/track/epipolar_search.h"
#include "p4/track/kalman_filter.h"

namespace p4 {
namespace {

// A rendered frame of camera 0 with the ball in view, per size (cached).
const I420Image& Frame(int width, int height) {
  static std::map<std::pair<int, int>, I420Image> cache;
  auto& image = cache[{width, height}];
  if (image.width() == 0) {
    const Rig rig = sim::ClubRig(1, width, height, false);
    sim::SceneOptions scene;
    sim::RenderOptions options;
    options.static_supersampling = 1;
    sim::CameraRenderer renderer(rig.cameras[0], scene, options);
    sim::FrameContent content;
    content.ball = {Eigen::Vector3d(0.4, 0.1, 0.3)};
    renderer.Render(content, 0, &image);
  }
  return image;
}

// The background model's update per frame (every row_stride-th block row, in turn), with the
// long-term model (lt:1, as the white ball's detector keeps it) or without.
void BM_BackgroundUpdate(benchmark::State& state) {
  const I420Image& image =
      Frame(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  segment::BackgroundOptions options;
  options.long_term = state.range(2) != 0;
  segment::BackgroundModel model(image.width(), image.height(), options);
  model.Update(image.View());
  for (auto _ : state) model.Update(image.View());
  state.SetItemsProcessed(state.iterations() * image.width() * image.height());
}
BENCHMARK(BM_BackgroundUpdate)
    ->ArgNames({"w", "h", "lt"})
    ->Args({640, 480, 0})
    ->Args({640, 480, 1})
    ->Args({1280, 720, 0})
    ->Args({1280, 720, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->Unit(benchmark::kMicrosecond);

// Whole-image search on the background (the ball found, unmixed and measured by coverage),
// after the model has learnt a picture without the ball.
void BM_ForegroundWholeImage(benchmark::State& state) {
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  const Rig rig = sim::ClubRig(1, w, h, false);
  sim::SceneOptions scene;
  sim::RenderOptions options;
  options.static_supersampling = 1;
  sim::CameraRenderer renderer(rig.cameras[0], scene, options);
  I420Image empty, with_ball;
  segment::BackgroundModel model(w, h, {});
  for (int k = 0; k < 20; ++k) {
    renderer.Render(sim::FrameContent{}, k, &empty);
    model.Update(empty.View());
  }
  sim::FrameContent content;
  content.ball = {Eigen::Vector3d(0.4, 0.1, 0.3)};
  renderer.Render(content, 21, &with_ball);
  segment::ForegroundFinder finder;
  std::vector<segment::CoverageRegion> regions;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        finder.Find(with_ball.View(), model, segment::BallColour::Orange(), {}, {}, &regions));
  }
  state.counters["regions"] = static_cast<double>(regions.size());
}
BENCHMARK(BM_ForegroundWholeImage)
    ->ArgNames({"w", "h"})
    ->Args({640, 480})
    ->Args({1280, 720})
    ->Unit(benchmark::kMicrosecond);

// A webcam's frame with a faint streak: a 4 px ball smeared over 1/30 s at 12 m/s (about 45 px
// at 640x480), and the background model learnt without it.
struct StreakFrame {
  Camera camera;
  I420Image with_ball;
  segment::BackgroundModel model{640, 480, {}};
  Eigen::Vector3d p{0.4, 0.1, 0.3}, v{12.0, -1.0, 1.5};
};
const StreakFrame& Streak() {
  static const StreakFrame frame = [] {
    StreakFrame f;
    f.camera = sim::ClubRig(1, 640, 480, false).cameras[0];
    sim::SceneOptions scene;
    sim::RenderOptions options;
    options.static_supersampling = 1;
    sim::CameraRenderer renderer(f.camera, scene, options);
    I420Image empty;
    for (int k = 0; k < 20; ++k) {
      renderer.Render(sim::FrameContent{}, k, &empty);
      f.model.Update(empty.View());
    }
    sim::FrameContent content;
    for (int s = 0; s < 48; ++s)
      content.ball.push_back(f.p + f.v * ((s + 0.5) / 48.0 - 0.5) / 30.0);
    renderer.Render(content, 21, &f.with_ball);
    return f;
  }();
  return frame;
}

// The streak search along a predicted path (webcams), the prediction 1 cm off; the search
// reaches 8 px.
void BM_StreakSearch(benchmark::State& state) {
  const StreakFrame& f = Streak();
  const Camera& camera = f.camera;
  const Eigen::Vector3d guess = f.p + Eigen::Vector3d(0.01, 0.0, 0.0);
  const auto a = camera.Project(guess - f.v / 50.0), b = camera.Project(guess + f.v / 50.0),
             m = camera.Project(guess);
  const double diameter = 0.04 * camera.fx / (camera.cam_from_world * f.p).z();
  segment::StreakSearch search;
  bool found = false;
  for (auto _ : state) {
    const auto hit =
        search.Find(f.with_ball.View(), f.model, segment::BallColour::Orange(), m->x(), m->y(),
                    b->x() - a->x(), b->y() - a->y(), (*b - *a).norm(), diameter, {});
    found = hit.has_value();
    benchmark::DoNotOptimize(hit);
  }
  state.counters["found"] = found;
}
BENCHMARK(BM_StreakSearch)->Unit(benchmark::kMicrosecond);

// The same frame searched whole for streaks with no prediction (no track yet). Every call after
// the first finds the streak where it was in the "last frame" and leaves it out: the offset is
// the first call's.
void BM_StreakFinder(benchmark::State& state) {
  const StreakFrame& f = Streak();
  segment::StreakFinder finder;
  std::vector<segment::StreakCandidate> found;
  finder.Find(f.with_ball.View(), f.model, segment::BallColour::Orange(), {}, &found);
  const auto truth = f.camera.Project(f.p);
  state.counters["best_off_px"] =
      found.empty() ? -1.0 : std::hypot(found[0].cx - truth->x(), found[0].cy - truth->y());
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        finder.Find(f.with_ball.View(), f.model, segment::BallColour::Orange(), {}, &found));
  }
}
BENCHMARK(BM_StreakFinder)->Unit(benchmark::kMicrosecond);

void BM_SegmentFullFrame(benchmark::State& state) {
  const I420Image& image =
      Frame(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto classes = segment::DefaultOrangeBall();
  const auto lut = classes.BuildLut();
  segment::SegmentOptions options;
  options.mask = classes.MaskOf("ball");
  options.chroma_first = state.range(2) != 0;
  segment::BlobFinder finder;
  std::vector<segment::Region> regions;
  for (auto _ : state) {
    benchmark::DoNotOptimize(finder.Find(image.View(), lut, {}, options, &regions));
  }
  state.SetItemsProcessed(state.iterations() * image.width() * image.height());
}
BENCHMARK(BM_SegmentFullFrame)
    ->ArgNames({"w", "h", "chroma_first"})
    ->Args({320, 240, 1})
    ->Args({640, 480, 1})
    ->Args({640, 480, 0})
    ->Args({1280, 720, 1})
    ->Args({1920, 1080, 1})
    ->Unit(benchmark::kMicrosecond);

void BM_SegmentRoi(benchmark::State& state) {
  const I420Image& image = Frame(640, 480);
  const auto classes = segment::DefaultOrangeBall();
  const auto lut = classes.BuildLut();
  segment::SegmentOptions options;
  options.mask = classes.MaskOf("ball");
  segment::BlobFinder finder;
  std::vector<segment::Region> regions;
  const int size = static_cast<int>(state.range(0));
  const auto roi = segment::Roi::Around(320, 240, size, size, 640, 480);
  for (auto _ : state) {
    benchmark::DoNotOptimize(finder.Find(image.View(), lut, roi, options, &regions));
  }
}
BENCHMARK(BM_SegmentRoi)->Arg(40)->Arg(120)->Arg(240)->Unit(benchmark::kMicrosecond);

void BM_OpenCvBaseline(benchmark::State& state) {
  const I420Image& image =
      Frame(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const int w = image.width(), h = image.height();
  cv::Mat bgr, hsv, mask, labels, stats, centroids;
  for (auto _ : state) {
    const cv::Mat yuv(h * 3 / 2, w, CV_8UC1, const_cast<uint8_t*>(image.y()));
    cv::cvtColor(yuv, bgr, cv::COLOR_YUV2BGR_I420);
    cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
    cv::inRange(hsv, cv::Scalar(5, 120, 80), cv::Scalar(25, 255, 255), mask);
    benchmark::DoNotOptimize(cv::connectedComponentsWithStats(mask, labels, stats, centroids));
  }
}
BENCHMARK(BM_OpenCvBaseline)->Args({640, 480})->Args({1920, 1080})->Unit(benchmark::kMicrosecond);

void BM_Triangulate(benchmark::State& state) {
  const Rig rig = sim::ClubRig(static_cast<int>(state.range(0)), 1280, 720, false);
  const Eigen::Vector3d point(0.3, 0.1, 0.25);
  std::vector<Observation> observations;
  observations.reserve(static_cast<std::size_t>(rig.size()));
  for (int c = 0; c < rig.size(); ++c)
    observations.push_back({c, rig.cameras[c].Project(point).value()});
  for (auto _ : state) benchmark::DoNotOptimize(TriangulateObservations(rig.cameras, observations));
}
BENCHMARK(BM_Triangulate)->Arg(2)->Arg(3)->Arg(8);

void BM_EpipolarDistance(benchmark::State& state) {
  const Rig rig = sim::ClubRig(2, 1280, 720, false);
  const Eigen::Vector3d point(0.3, 0.1, 0.25);
  const Eigen::Vector2d a = rig.cameras[0].Project(point).value(),
                        b = rig.cameras[1].Project(point).value();
  for (auto _ : state)
    benchmark::DoNotOptimize(EpipolarDistance(rig.cameras[0], a, rig.cameras[1], b));
}
BENCHMARK(BM_EpipolarDistance);

// The ball of camera 1's view looked for along its epipolar segment in camera 0's picture
// (FrameSetOptions::search_epipolars): arg 1, the ball there (found); 0, a view 30 cm beside it
// (every fit along the segment fails: the worst case).
void BM_EpipolarSearch(benchmark::State& state) {
  const Rig rig = sim::ClubRig(2, 1280, 720, false);
  const Eigen::Vector3d ball(0.4, 0.1, 0.3);
  const Eigen::Vector3d point = state.range(0) ? ball : Eigen::Vector3d(0.4, 0.4, 0.3);
  const Eigen::Vector2d view = rig.cameras[1].Project(point).value();
  const double diameter =
      2.0 * 0.02 * rig.cameras[1].fx / (rig.cameras[1].cam_from_world * point).z();
  const double orange[3] = {137.0, 65.0, 199.0};
  const I420Image& image = Frame(1280, 720);
  int fits = 0;
  for (auto _ : state) {
    const auto found = track::SearchAlongEpipolar(rig.cameras[1], view, diameter, orange,
                                                  rig.cameras[0], image.View());
    benchmark::DoNotOptimize(found);
    fits = found ? found->fits : -1;
  }
  state.counters["fits"] = fits;
}
BENCHMARK(BM_EpipolarSearch)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

void BM_KalmanPredictUpdate(benchmark::State& state) {
  track::KalmanFilter filter{track::KalmanOptions{}};
  const Eigen::Vector3d z(0.3, 0.1, 0.25);
  const Eigen::Matrix3d r = 1e-6 * Eigen::Matrix3d::Identity();
  for (auto _ : state) {
    filter.Predict(1.0 / 120.0);
    filter.Update(z, r);
    benchmark::DoNotOptimize(filter.state());
  }
}
BENCHMARK(BM_KalmanPredictUpdate);

}  // namespace
}  // namespace p4

BENCHMARK_MAIN();
