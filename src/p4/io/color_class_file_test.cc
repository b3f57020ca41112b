#include "p4/io/color_class_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"
#include "p4/io/test_folder.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

class ColorClassFileTest : public testing::TestFolder {
 protected:
  ColorClassFileTest() : TestFolder("p4_classes_test_") {}
};

// A learning run saves its classes with the ball's lit colour; read back, both are as written
// (a run given the file with --classes is the learning run again).
TEST_F(ColorClassFileTest, TheBallsColourTravelsWithItsClasses) {
  const segment::ColorClassSet classes = segment::NamedBall("yellow");
  segment::BallColour ball;
  ball.lit = {181.5f, 62.25f, 151.0f};
  WriteColorClasses(classes, Path("learnt.yaml"), &ball);
  const segment::ColorClassSet read = ReadColorClasses(Path("learnt.yaml"));
  ASSERT_EQ(read.classes.size(), classes.classes.size());
  for (std::size_t i = 0; i < classes.classes.size(); ++i) {
    EXPECT_EQ(read.classes[i].name, classes.classes[i].name);
    EXPECT_EQ(read.classes[i].y, classes.classes[i].y);
    EXPECT_EQ(read.classes[i].u, classes.classes[i].u);
    EXPECT_EQ(read.classes[i].v, classes.classes[i].v);
  }
  const auto lit = ReadColorClassFile(Path("learnt.yaml")).ball;
  ASSERT_TRUE(lit.has_value());
  EXPECT_FLOAT_EQ(lit->lit.y, 181.5f);
  EXPECT_FLOAT_EQ(lit->lit.u, 62.25f);
  EXPECT_FLOAT_EQ(lit->lit.v, 151.0f);
  // Written without it (a hand-made file): no colour, the classes alone.
  WriteColorClasses(classes, Path("plain.yaml"));
  EXPECT_FALSE(ReadColorClassFile(Path("plain.yaml")).ball.has_value());
  EXPECT_EQ(ReadColorClasses(Path("plain.yaml")).classes.size(), classes.classes.size());
}

TEST_F(ColorClassFileTest, ABadBallColourIsNamed) {
  const std::string classes =
      "classes:\n  - { name: ball, y: [100, 200], u: [50, 100], v: [180, 240] }\n";
  const auto message = [&](const std::string& lit) {
    const std::string path = Write("bad.yaml", classes + "ball_lit: " + lit + "\n");
    try {
      ReadColorClassFile(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("[137, 65]").find("'ball_lit' must be [y, u, v]"), std::string::npos);
  EXPECT_NE(message("[137, 300, 200]").find("ball_lit[1]: '300' is not a level in 0-255"),
            std::string::npos);
  EXPECT_NE(message("[137, orange, 200]").find("ball_lit[1]: 'orange'"), std::string::npos);
  EXPECT_NE(message("[137, 65, 200]").find("no error"), std::string::npos);
}

}  // namespace
}  // namespace p4
