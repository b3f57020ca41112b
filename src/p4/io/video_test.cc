#include <gtest/gtest.h>

#include <filesystem>

#include "p4/core/error.h"
#include "p4/io/video_reader.h"
#include "p4/io/video_writer.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

I420Image Pattern(int w, int h, int k) {
  I420Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      image.y()[y * w + x] = static_cast<uint8_t>((x * 3 + y + 7 * k) % 220 + 16);
  }
  for (int i = 0; i < w * h / 4; ++i) {
    image.u()[i] = static_cast<uint8_t>(100 + (i + k) % 50);
    image.v()[i] = static_cast<uint8_t>(140 - (i * 3 + k) % 40);
  }
  return image;
}

TEST(Video, LosslessRoundTripKeepsEveryByteAndTime) {
  const std::string path = (fs::temp_directory_path() / "p4_video_test.mkv").string();
  VideoWriterOptions options;
  options.width = 64;
  options.height = 48;
  options.fps = 120;
  options.codec = VideoCodec::kFFV1;
  {
    VideoWriter writer(path, options);
    for (int k = 0; k < 10; ++k) writer.Write(Pattern(64, 48, k));
    writer.Close();
  }
  VideoReader reader(path);
  EXPECT_EQ(reader.info().width, 64);
  EXPECT_NEAR(reader.info().fps, 120.0, 1e-6);
  I420Image frame;
  TimeNs pts = 0;
  int k = 0;
  while (reader.Read(&frame, &pts)) {
    EXPECT_EQ(frame.bytes(), Pattern(64, 48, k).bytes()) << k;
    EXPECT_NEAR(ToSeconds(pts), k / 120.0, 1e-3) << k;
    ++k;
  }
  EXPECT_EQ(k, 10);
  fs::remove(path);
}

TEST(Video, MissingFileIsNamed) {
  try {
    VideoReader reader("/nonexistent/p4.mp4");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/p4.mp4"), std::string::npos);
  }
  VideoWriterOptions odd;
  odd.width = 63;
  odd.height = 48;
  EXPECT_THROW(VideoWriter("/tmp/p4_odd.mp4", odd), Error);
}

}  // namespace
}  // namespace p4
