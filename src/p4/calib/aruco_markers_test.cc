#include "p4/calib/aruco_markers.h"

#include <gtest/gtest.h>

#include <opencv2/aruco.hpp>

#include "p4/core/error.h"
#include "p4/sim/camera_layout.h"
#include "p4/sim/renderer.h"

namespace p4 {
namespace {

TEST(ArucoModules, MatchOpenCvsDictionary) {
  int cells = 0;
  const auto black = ArucoModules("DICT_4X4_50", 7, &cells);
  ASSERT_EQ(cells, 6);
  for (int i = 0; i < 6; ++i) {  // the border is black
    EXPECT_EQ(black[i], 1);
    EXPECT_EQ(black[static_cast<std::size_t>(30 + i)], 1);
    EXPECT_EQ(black[i * 6], 1);
    EXPECT_EQ(black[i * 6 + 5], 1);
  }
  EXPECT_THROW(ArucoDictionaryId("DICT_9X9_1"), Error);
  EXPECT_THROW(ArucoModules("DICT_4X4_50", 50, &cells), Error);
}

// The simulator's markers, rendered by one camera, are found by OpenCV where the rig projects
// their world corners: the scene, the layout and the camera model agree.
TEST(ArucoModules, RenderedTableMarkersAreDetectedWhereTheyProject) {
  const Rig rig = sim::ClubRig(3, 1280, 720, false);
  const Camera& camera = rig.cameras[2];  // behind B
  sim::SceneOptions scene;
  scene.players = false;
  scene.markers = sim::TableCornerMarkers(0.15);
  for (auto& m : scene.markers) m.black = ArucoModules("DICT_4X4_50", m.id, &m.cells);
  sim::RenderOptions options;
  options.static_supersampling = 4;
  sim::CameraRenderer renderer(camera, scene, options);
  I420Image frame;
  renderer.Render(sim::FrameContent{}, 0, &frame);
  const cv::Mat gray(frame.height(), frame.width(), CV_8UC1, frame.y());

  const auto dict = cv::aruco::getPredefinedDictionary(ArucoDictionaryId("DICT_4X4_50"));
  auto params = cv::aruco::DetectorParameters::create();
  params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  params->cornerRefinementWinSize = 2;  // markers are 30-40 px: larger windows see the bits
  std::vector<int> ids;
  std::vector<std::vector<cv::Point2f>> corners;
  cv::aruco::detectMarkers(gray, dict, corners, ids, params);
  ASSERT_EQ(ids.size(), 4u);
  double worst = 0.0, worst_centre = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    Eigen::Vector2d detected_centre = Eigen::Vector2d::Zero(), projected_centre = detected_centre;
    ASSERT_GE(ids[i], 0);
    ASSERT_LT(ids[i], 4);
    const auto& quad = scene.markers[ids[i]];
    for (int k = 0; k < 4; ++k) {
      const auto px = camera.Project(quad.corners[k]);
      ASSERT_TRUE(px.has_value());
      const double error = std::hypot(corners[i][k].x - px->x(), corners[i][k].y - px->y());
      worst = std::max(worst, error);
      detected_centre += 0.25 * Eigen::Vector2d(corners[i][k].x, corners[i][k].y);
      projected_centre += 0.25 * *px;
    }
    worst_centre = std::max(worst_centre, (detected_centre - projected_centre).norm());
  }
  // The detector's own corner error on 30-40 px markers is ~1-2 px; it cancels on the centre.
  EXPECT_LT(worst, 2.0);
  EXPECT_LT(worst_centre, 0.6);
  std::printf("marker corner error: worst %.3f px, worst centre %.3f px\n", worst, worst_centre);
}

}  // namespace
}  // namespace p4
