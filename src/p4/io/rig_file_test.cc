#include "p4/io/rig_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"
#include "p4/geometry/look_at.h"
#include "p4/io/test_folder.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

class RigFileTest : public testing::TestFolder {
 protected:
  RigFileTest() : TestFolder("p4_rig_test_") {}

  // Expects ReadRig to fail with a message that contains every fragment.
  void ExpectError(const std::string& path, std::initializer_list<std::string> fragments) {
    try {
      ReadRig(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      for (const auto& f : fragments) {
        EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what() << " lacks " << f;
      }
    }
  }

  static Rig MakeRig() {
    Rig rig;
    for (int i = 0; i < 2; ++i) {
      Camera c;
      c.name = "cam" + std::to_string(i);
      c.width = 1280;
      c.height = 720;
      c.fx = 1000.5 + i;
      c.fy = 999.25;
      c.cx = 640.125;
      c.cy = 359.5;
      c.distortion = {-0.1, 0.02, 0.001, -0.002, 0.003};
      c.cam_from_world = LookAt({i ? 4.0 : -4.0, -1.0, 2.0}, {0.0, 0.0, 0.0});
      rig.cameras.push_back(c);
    }
    return rig;
  }
};

const char* kGoodCamera = R"(
   - name: cam0
     image_width: 1280
     image_height: 720
     camera_matrix: !!opencv-matrix
        rows: 3
        cols: 3
        dt: d
        data: [ 1000., 0., 640., 0., 1000., 360., 0., 0., 1. ]
     distortion_coefficients: !!opencv-matrix
        rows: 1
        cols: 5
        dt: d
        data: [ 0., 0., 0., 0., 0. ]
     rotation: !!opencv-matrix
        rows: 3
        cols: 3
        dt: d
        data: [ 1., 0., 0., 0., 0., -1., 0., 1., 0. ]
     translation: !!opencv-matrix
        rows: 3
        cols: 1
        dt: d
        data: [ 0., 0.5, 3. ]
)";

std::string YamlWith(const std::string& camera) { return "%YAML:1.0\n---\ncameras:\n" + camera; }

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST_F(RigFileTest, YamlAndJsonRoundTrip) {
  const Rig rig = MakeRig();
  for (const char* name : {"rig.yaml", "rig.json"}) {
    const std::string path = (dir_ / name).string();
    WriteRig(rig, path);
    const Rig back = ReadRig(path);
    ASSERT_EQ(back.size(), 2);
    for (int i = 0; i < 2; ++i) {
      const Camera& a = rig.cameras[i];
      const Camera& b = back.cameras[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.width, b.width);
      EXPECT_DOUBLE_EQ(a.fx, b.fx);
      EXPECT_DOUBLE_EQ(a.cy, b.cy);
      for (int k = 0; k < 5; ++k) EXPECT_DOUBLE_EQ(a.distortion[k], b.distortion[k]);
      EXPECT_LT((a.cam_from_world.rotation - b.cam_from_world.rotation).norm(), 1e-15);
      EXPECT_LT((a.cam_from_world.translation - b.cam_from_world.translation).norm(), 1e-15);
    }
  }
}

TEST_F(RigFileTest, ReadsTheDesignExampleAndHandWrittenJson) {
  const Rig rig = ReadRig(Write("design.yaml", YamlWith(kGoodCamera)));
  ASSERT_EQ(rig.size(), 1);
  EXPECT_DOUBLE_EQ(rig.cameras[0].cx, 640.0);
  EXPECT_NEAR((rig.cameras[0].Center() - Eigen::Vector3d(0.0, -3.0, 0.5)).norm(), 0.0, 1e-12);
  const Rig json = ReadRig(Write("hand.json", R"({"cameras": [{"name": "c", "image_width": 640,
      "image_height": 480, "camera_matrix": [[500, 0, 320], [0, 500, 240], [0, 0, 1]],
      "rotation": [1, 0, 0, 0, 1, 0, 0, 0, 1], "translation": [0, 0, 2]}]})"));
  ASSERT_EQ(json.size(), 1);
  EXPECT_DOUBLE_EQ(json.cameras[0].fy, 500.0);
  EXPECT_DOUBLE_EQ(json.cameras[0].distortion[0], 0.0);
}

TEST_F(RigFileTest, CameraClocksAreOptionalKeys) {
  // Without the keys: in step (offset unknown, taken as 0), global shutter.
  const Rig plain = ReadRig(Write("plain.yaml", YamlWith(kGoodCamera)));
  EXPECT_TRUE(plain.cameras[0].clock.InStep());
  EXPECT_FALSE(plain.cameras[0].clock.has_offset);
  // With them, in YAML and JSON, and written back only where they say something.
  Rig rig = MakeRig();
  rig.cameras[1].clock.time_offset_s = -0.123456789;
  rig.cameras[1].clock.has_offset = true;
  rig.cameras[1].clock.clock_rate = 1.0 + 35e-6;
  rig.cameras[1].clock.line_time_s = 20e-3 / 1080;
  for (const char* name : {"clock.yaml", "clock.json"}) {
    const std::string path = (dir_ / name).string();
    WriteRig(rig, path);
    const Rig back = ReadRig(path);
    EXPECT_TRUE(back.cameras[0].clock.InStep());
    EXPECT_FALSE(back.cameras[0].clock.has_offset);
    const CameraClock& c = back.cameras[1].clock;
    EXPECT_TRUE(c.has_offset);
    EXPECT_DOUBLE_EQ(c.time_offset_s, -0.123456789);
    EXPECT_DOUBLE_EQ(c.clock_rate, 1.0 + 35e-6);
    EXPECT_DOUBLE_EQ(c.line_time_s, 20e-3 / 1080);
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("time_offset_s"), text.rfind("time_offset_s")) << "cam0 has no offset key";
  }
  // A world time and back: the offset, the drift and a row's delay.
  const CameraClock& c = rig.cameras[1].clock;
  const TimeNs stamp = FromSeconds(100.0);
  EXPECT_NEAR(ToSeconds(c.WorldTime(stamp)), -0.123456789 + 100.0 * (1.0 + 35e-6), 1e-9);
  EXPECT_EQ(c.Stamp(c.WorldTime(stamp)), stamp);
  EXPECT_NEAR(c.RowDelay(1079.0), 20e-3 * 1079.0 / 1080.0, 1e-15);
  // Bad values name the key.
  ExpectError(Write("rate.yaml", YamlWith(std::string(kGoodCamera) + "     clock_rate: 1.5\n")),
              {"rate.yaml", "cam0", "clock_rate"});
  ExpectError(Write("line.yaml", YamlWith(std::string(kGoodCamera) + "     line_time_s: -0.001\n")),
              {"line.yaml", "cam0", "line_time_s"});
  ExpectError(
      Write("offset.yaml", YamlWith(std::string(kGoodCamera) + "     time_offset_s: soon\n")),
      {"offset.yaml", "cam0", "time_offset_s", "number"});
}

TEST_F(RigFileTest, EveryKindOfBadFileIsNamed) {
  ExpectError((dir_ / "missing.yaml").string(), {"missing.yaml", "no such file"});
  ExpectError(Write("garbage.yaml", "%YAML:1.0\n---\ncameras: [ {{{ \n"), {"garbage.yaml"});
  ExpectError(Write("nocams.yaml", "%YAML:1.0\n---\nfoo: 1\n"), {"nocams.yaml", "cameras"});
  ExpectError(Write("nokey.yaml", YamlWith(Replace(kGoodCamera, "image_height: 720", ""))),
              {"nokey.yaml", "cameras[0] 'cam0'", "image_height"});
  ExpectError(Write("size.yaml", YamlWith(Replace(Replace(kGoodCamera, "rows: 3\n        cols: 1",
                                                          "rows: 2\n        cols: 1"),
                                                  "data: [ 0., 0.5, 3. ]", "data: [ 0., 0.5 ]"))),
              {"size.yaml", "translation", "3x1", "2x1"});
  ExpectError(Write("nan.yaml", YamlWith(Replace(kGoodCamera, "data: [ 0., 0.5, 3. ]",
                                                 "data: [ 0., .nan, 3. ]"))),
              {"nan.yaml", "translation", "not finite"});
  ExpectError(
      Write("rot.yaml", YamlWith(Replace(kGoodCamera, "[ 1., 0., 0., 0., 0., -1., 0., 1., 0. ]",
                                         "[ 1., 0., 0., 0., 1., 0., 0., 1., 0. ]"))),
      {"rot.yaml", "cam0", "rotation"});
  ExpectError(Write("focal.yaml", YamlWith(Replace(kGoodCamera, "[ 1000., 0., 640., 0., 1000.",
                                                   "[ 0., 0., 640., 0., 1000."))),
              {"focal.yaml", "cam0", "focal"});
  ExpectError(Write("twice.yaml", YamlWith(std::string(kGoodCamera) + kGoodCamera)),
              {"twice.yaml", "cam0", "twice"});
  // Found by fuzzing (fuzz/corpus/rig_file/regression_*): a matrix whose rows x cols overflows an
  // int, a root that is a list, and a file on which OpenCV's YAML parser never returned.
  ExpectError(Write("overflow.yaml", YamlWith(Replace(kGoodCamera, "rows: 3\n        cols: 1",
                                                      "rows: 2147483647\n        cols: 3"))),
              {"overflow.yaml", "translation"});
  ExpectError(Write("list.yaml", "%YAML:1.0\n---\n- 1\n- 2\n"), {"list.yaml", "map"});
  ExpectError(Write("loop.yaml", "%YAML:1.0\n---  - 2\n-\n"), {"loop.yaml"});
}

}  // namespace
}  // namespace p4
