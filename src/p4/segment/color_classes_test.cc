#include "p4/segment/color_classes.h"

#include <gtest/gtest.h>

#include <random>

namespace p4::segment {
namespace {

uint8_t ToY(double r, double g, double b) {
  return static_cast<uint8_t>(std::lround(16 + 219 * (0.299 * r + 0.587 * g + 0.114 * b)));
}
uint8_t ToU(double r, double g, double b) {
  const double y = 0.299 * r + 0.587 * g + 0.114 * b;
  return static_cast<uint8_t>(std::lround(128 + 224 * (b - y) / 1.772));
}
uint8_t ToV(double r, double g, double b) {
  const double y = 0.299 * r + 0.587 * g + 0.114 * b;
  return static_cast<uint8_t>(std::lround(128 + 224 * (r - y) / 1.402));
}

TEST(ColorLut, ThirtyTwoClassesAtOnceMatchTheBoxes) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> byte(0, 255);
  ColorClassSet set;
  for (int k = 0; k < 32; ++k) {
    ColorClass c;
    c.name = "c" + std::to_string(k);
    for (auto* range : {&c.y, &c.u, &c.v}) {
      int a = byte(rng), b = byte(rng);
      if (a > b) std::swap(a, b);
      *range = {static_cast<uint8_t>(a), static_cast<uint8_t>(b)};
    }
    set.classes.push_back(c);
  }
  std::string error;
  ASSERT_TRUE(set.IsValid(&error)) << error;
  const ColorLut lut = set.BuildLut();
  for (int y = 0; y < 256; y += 3) {
    for (int u = 0; u < 256; u += 5) {
      for (int v = 0; v < 256; v += 7) {
        uint32_t expected = 0;
        for (int k = 0; k < 32; ++k) {
          if (set.classes[k].Contains(y, u, v)) expected |= 1u << k;
        }
        ASSERT_EQ(lut.Classify(y, u, v), expected) << y << " " << u << " " << v;
      }
    }
  }
  set.classes.push_back(set.classes[0]);
  EXPECT_FALSE(set.IsValid(&error));
  EXPECT_NE(error.find("32"), std::string::npos);
}

TEST(ColorClassSet, MasksByName) {
  const ColorClassSet set = DefaultOrangeBall();
  EXPECT_EQ(set.MaskOf("ball"), 0b111u);
  EXPECT_EQ(set.MaskOf("ball_dark"), 0b100u);
  EXPECT_EQ(set.MaskOf("shirt"), 0u);
  ColorClass bad{"bad", {10, 5}, {0, 255}, {0, 255}};
  std::string error;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_NE(error.find("bad"), std::string::npos);
}

TEST(DefaultOrangeBall, TakesTheShadedBallAndLeavesTheHall) {
  const ColorClassSet set = DefaultOrangeBall();
  const ColorLut lut = set.BuildLut();
  const uint32_t ball = set.MaskOf("ball");
  const auto in = [&](double r, double g, double b, double k) {
    return (lut.Classify(ToY(r * k, g * k, b * k), ToU(r * k, g * k, b * k),
                         ToV(r * k, g * k, b * k)) &
            ball) != 0;
  };
  for (double k : {0.6, 0.75, 0.9, 1.0}) EXPECT_TRUE(in(1.0, 0.42, 0.05, k)) << k;
  for (double k : {0.5, 0.7, 0.9, 1.0}) {
    EXPECT_FALSE(in(0.40, 0.17, 0.13, k)) << "red-brown floor " << k;
    EXPECT_FALSE(in(0.82, 0.60, 0.50, k)) << "skin " << k;
    EXPECT_FALSE(in(0.05, 0.17, 0.36, k)) << "blue table " << k;
    EXPECT_FALSE(in(0.93, 0.93, 0.93, k)) << "white line " << k;
  }
}

TEST(LearnClasses, BoxesCoverTheSamplesAndNotOtherColours) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 2.0);
  std::vector<YuvSample> samples;
  for (int i = 0; i < 3000; ++i) {
    const double k = 0.6 + 0.4 * (i % 100) / 100.0;  // shading from 60 % to 100 %
    const double r = 1.0 * k, g = 0.42 * k, b = 0.05 * k;
    samples.push_back({static_cast<uint8_t>(ToY(r, g, b) + noise(rng)),
                       static_cast<uint8_t>(ToU(r, g, b) + noise(rng)),
                       static_cast<uint8_t>(ToV(r, g, b) + noise(rng))});
  }
  ColorClassSet set;
  set.classes = LearnClasses(samples, "ball", 3);
  ASSERT_EQ(set.classes.size(), 3u);
  EXPECT_EQ(set.classes[2].name, "ball_2");
  const ColorLut lut = set.BuildLut();
  int covered = 0;
  for (const auto& s : samples) covered += lut.Classify(s.y, s.u, s.v) != 0;
  EXPECT_GT(covered, 0.97 * samples.size());
  EXPECT_EQ(lut.Classify(ToY(0.05, 0.17, 0.36), ToU(0.05, 0.17, 0.36), ToV(0.05, 0.17, 0.36)), 0u);
  EXPECT_EQ(lut.Classify(ToY(0.4, 0.17, 0.13), ToU(0.4, 0.17, 0.13), ToV(0.4, 0.17, 0.13)), 0u);
}

}  // namespace
}  // namespace p4::segment
