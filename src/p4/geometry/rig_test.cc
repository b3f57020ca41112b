#include "p4/geometry/rig.h"

#include <gtest/gtest.h>

#include "p4/geometry/test_cameras.h"

namespace p4 {
namespace {

TEST(Rig, FindsCamerasByName) {
  Rig rig{testing::ClubCameras()};
  EXPECT_EQ(rig.Find("end_b"), 2);
  EXPECT_EQ(rig.Find("nope"), -1);
  std::string error;
  EXPECT_TRUE(ValidateRig(rig, &error)) << error;
}

TEST(Rig, RejectsEmptyDuplicateAndBadCameras) {
  std::string error;
  EXPECT_FALSE(ValidateRig(Rig{}, &error));
  EXPECT_NE(error.find("no camera"), std::string::npos);

  Rig twice{testing::ClubCameras()};
  twice.cameras[1].name = "side";
  EXPECT_FALSE(ValidateRig(twice, &error));
  EXPECT_NE(error.find("cameras[1] 'side'"), std::string::npos) << error;

  Rig bad{testing::ClubCameras()};
  bad.cameras[3].fy = -5.0;
  EXPECT_FALSE(ValidateRig(bad, &error));
  EXPECT_NE(error.find("cameras[3] 'other_side'"), std::string::npos) << error;
  EXPECT_NE(error.find("focal"), std::string::npos) << error;
}

}  // namespace
}  // namespace p4
