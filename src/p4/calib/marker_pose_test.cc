#include "p4/calib/marker_pose.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "p4/calib/aruco_markers.h"
#include "p4/sim/camera_layout.h"
#include "p4/sim/renderer.h"

namespace p4::calib {
namespace {

MarkerLayout LayoutOf(const std::vector<sim::MarkerQuad>& quads) {
  MarkerLayout layout;
  for (const auto& q : quads) layout.corners[q.id] = q.corners;
  return layout;
}

// What each camera of a simulated club rig sees of 12 cm markers on the table corners, over a
// few noisy frames.
std::vector<std::vector<MarkerObservation>> RenderedMarkers(const Camera& camera,
                                                            const sim::SceneOptions& scene,
                                                            int frames) {
  sim::RenderOptions options;
  sim::CameraRenderer renderer(camera, scene, options);
  std::vector<std::vector<MarkerObservation>> seen;
  I420Image frame;
  for (int i = 0; i < frames; ++i) {
    renderer.Render(sim::FrameContent{}, i, &frame);
    const cv::Mat gray(frame.height(), frame.width(), CV_8UC1, frame.y());
    seen.push_back(DetectMarkers(gray, "DICT_4X4_50"));
  }
  return seen;
}

sim::SceneOptions MarkerScene() {
  sim::SceneOptions scene;
  scene.markers = sim::TableCornerMarkers(0.12);
  for (auto& m : scene.markers) m.black = ArucoModules("DICT_4X4_50", m.id, &m.cells);
  return scene;
}

// Issue target: camera centres within 5 mm and rotations within 0.1 degree of the truth.
TEST(SolveMarkerPose, RecoversEveryCameraOfASimulatedRig) {
  const Rig rig = sim::ClubRig(4, 1280, 720, false);
  const sim::SceneOptions scene = MarkerScene();
  const MarkerLayout layout = LayoutOf(scene.markers);
  for (const Camera& truth : rig.cameras) {
    const auto observed = AverageObservations(RenderedMarkers(truth, scene, 5));
    std::string error;
    const auto result =
        SolveMarkerPose(truth, truth.name, truth.width, truth.height, observed, layout, 1, &error);
    ASSERT_TRUE(result) << truth.name << ": " << error;
    const Camera& c = result->fit.camera;
    const double centre_mm = 1000.0 * (c.Center() - truth.Center()).norm();
    const double angle_deg =
        Eigen::AngleAxisd(c.cam_from_world.rotation.transpose() * truth.cam_from_world.rotation)
            .angle() *
        180.0 / M_PI;
    std::printf("%s: %zu markers, centre %.2f mm, rotation %.4f deg, rms %.3f px\n",
                truth.name.c_str(), result->used.size(), centre_mm, angle_deg, result->fit.rms_px);
    EXPECT_GE(result->used.size(), 2u) << truth.name;
    EXPECT_LT(centre_mm, 5.0) << truth.name;
    EXPECT_LT(angle_deg, 0.1) << truth.name;
    EXPECT_LT(result->fit.rms_px, 1.0) << truth.name;
  }
}

// The edge-fitted corners sit where the rig projects the markers' world corners, to a fraction of
// the 1-2 px of OpenCV's own refinement on these 20-40 px markers (aruco_markers_test).
TEST(RefineMarkerCorners, PutsCornersWhereTheyProject) {
  const Rig rig = sim::ClubRig(4, 1280, 720, false);
  const sim::SceneOptions scene = MarkerScene();
  double worst = 0.0;
  int corners = 0;
  for (const Camera& camera : rig.cameras) {
    const auto frames = RenderedMarkers(camera, scene, 1);
    for (const MarkerObservation& m : frames[0]) {
      ASSERT_GE(m.id, 0);
      ASSERT_LT(m.id, 4);
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d truth = camera.Project(scene.markers[m.id].corners[k]).value();
        worst = std::max(worst, (m.corners[k] - truth).norm());
        ++corners;
      }
    }
  }
  std::printf("%d corners, worst error %.3f px\n", corners, worst);
  EXPECT_GE(corners, 40);
  EXPECT_LT(worst, 0.75);
}

TEST(SolveMarkerPose, SaysWhichMarkersAreMissing) {
  MarkerLayout layout;
  layout.corners[0] = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0),
                       Eigen::Vector3d(0.1, 0.1, 0), Eigen::Vector3d(0, 0.1, 0)};
  MarkerObservation stranger;
  stranger.id = 17;
  std::string error;
  EXPECT_FALSE(SolveMarkerPose(std::nullopt, "cam0", 1280, 720, {stranger}, layout, 1, &error));
  EXPECT_EQ(error, "sees 0 marker(s) of the layout, 1 needed (found ids not in the layout: 17)");
}

TEST(AverageObservations, AveragesCornersAndDropsRareMarkers) {
  MarkerObservation a{3, {}}, b{3, {}}, rare{9, {}};
  for (int k = 0; k < 4; ++k) {
    a.corners[k] = {10.0 * k, 1.0};
    b.corners[k] = {10.0 * k, 2.0};
  }
  const auto avg = AverageObservations({{a}, {b, rare}, {a}, {b}});
  ASSERT_EQ(avg.size(), 1u);
  EXPECT_EQ(avg[0].id, 3);
  EXPECT_DOUBLE_EQ(avg[0].corners[2].x(), 20.0);
  EXPECT_DOUBLE_EQ(avg[0].corners[2].y(), 1.5);
}

}  // namespace
}  // namespace p4::calib
