#include "p4/io/calib_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"
#include "p4/io/test_folder.h"
#include "p4/io/truth_files.h"
#include "p4/sim/scene.h"

namespace p4 {
namespace {

class CalibFilesTest : public testing::TestFolder {
 protected:
  CalibFilesTest() : TestFolder("p4_calib_files_") {}
  // The message of the p4::Error that f throws, or "" when it does not.
  template <typename F>
  static std::string ErrorOf(F f) {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(CalibFilesTest, ReadsTheSimulatorsMarkerLayout) {
  const auto quads = sim::TableCornerMarkers(0.12);
  const std::string path = (dir_ / "markers.yaml").string();
  WriteMarkerLayout(path, quads, "DICT_4X4_50");
  const calib::MarkerLayout layout = ReadMarkerLayout(path);
  EXPECT_EQ(layout.dictionary, "DICT_4X4_50");
  ASSERT_EQ(layout.corners.size(), quads.size());
  for (const auto& q : quads) {
    for (int k = 0; k < 4; ++k) {
      EXPECT_LT((layout.corners.at(q.id)[k] - q.corners[k]).norm(), 1e-9);
    }
  }
}

TEST_F(CalibFilesTest, ReadsAHandWrittenLayoutAndNamesWhatIsWrong) {
  const auto layout = ReadMarkerLayout(Write("a.yaml", R"(%YAML:1.0
---
markers:
  - { id: 3, corners: [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]] }
)"));
  ASSERT_EQ(layout.corners.count(3), 1u);
  EXPECT_DOUBLE_EQ(layout.corners.at(3)[2].y(), 0.1);
  EXPECT_NE(ErrorOf([&] {
              ReadMarkerLayout(Write("b.yaml", R"(%YAML:1.0
---
markers:
  - { id: 3, corners: [[0, 0, 0], [0.1, 0, 0]] }
)"));
            }).find("marker 0 (id 3): 'corners' must be 4 points x,y,z, got 6 numbers"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadMarkerLayout((dir_ / "none.yaml").string()); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ReadMarkerLayout(Write("c.yaml", "%YAML:1.0\n---\nfoo: 1\n"));
            }).find("missing 'markers' list"),
            std::string::npos);
}

TEST_F(CalibFilesTest, ReadsTheRealTablePoints) {
  const auto points = ReadPointMatches(std::string(P4_SHARED_DATA) +
                                       "/detections/two_phones_30fps/cam0_table_points.csv");
  ASSERT_EQ(points.size(), 6u);
  EXPECT_DOUBLE_EQ(points[0].pixel.x(), 247.0);
  EXPECT_DOUBLE_EQ(points[4].world.z(), 0.15);
  EXPECT_NE(ErrorOf([&] {
              ReadPointMatches(Write("p.csv", "u,v,x,y,z\n1,2,3,4\n"));
            }).find("p.csv: line 2: expected 5 fields"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ReadPointMatches(Write("q.csv", "u,v,x,y,z\n1,2,3,4,z\n"));
            }).find("line 2: 'z' is not a number"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadPointMatches(Write("r.csv", "x,y\n")); }).find("expected the header"),
            std::string::npos);
}

TEST_F(CalibFilesTest, ReadsAFolderOfImagesInOrder) {
  const auto frames =
      ReadGrayFrames(std::string(P4_SHARED_DATA) + "/calibration/opencv_stereo_chessboard", 100, 1);
  ASSERT_EQ(frames.size(), 26u);  // left and right, 13 each
  EXPECT_EQ(frames.front().name, "left01.jpg");
  EXPECT_EQ(frames.front().gray.type(), CV_8UC1);
  EXPECT_EQ(frames.front().gray.cols, 640);
  EXPECT_NE(ErrorOf([&] { ReadGrayFrames(dir_.string(), 10, 1); }).find("no image files"),
            std::string::npos);
  const auto left = ReadGrayFrames(
      std::string(P4_SHARED_DATA) + "/calibration/opencv_stereo_chessboard/left*.jpg", 100, 1);
  ASSERT_EQ(left.size(), 13u);
  EXPECT_EQ(left.back().name, "left14.jpg");
  EXPECT_NE(ErrorOf([&] {
              ReadGrayFrames((dir_ / "x*.png").string(), 10, 1);
            }).find("no image file matches"),
            std::string::npos);
}

}  // namespace
}  // namespace p4
