#include "p4/pipeline/frame_set_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>

#include "p4/core/error.h"
#include "p4/io/video_writer.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

constexpr double kMs = 1.001e-3;  // Matroska's time resolution

// A clip of `frames` grey frames of 64x48 (or the size given) at `fps`, lossless (frame k stamped
// k / fps, which Matroska keeps to the millisecond) or in the codec given.
std::string WriteClip(const std::string& name, int fps, int frames, int width = 64, int height = 48,
                      VideoCodec codec = VideoCodec::kFFV1) {
  std::string path = (fs::temp_directory_path() / name).string();
  VideoWriterOptions options;
  options.width = width;
  options.height = height;
  options.fps = fps;
  options.codec = codec;
  VideoWriter writer(path, options);
  I420Image image(width, height);
  for (int k = 0; k < frames; ++k) writer.Write(image);
  writer.Close();
  return path;
}

TEST(FrameSetReader, GroupsTheCamerasFramesByTime) {
  const std::string a = WriteClip("p4_fsr_a.mkv", 30, 6), b = WriteClip("p4_fsr_b.mkv", 30, 4);
  FrameSetReader reader({a, b});
  FrameSet set;
  std::vector<TimeNs> times;
  int both = 0;
  while (reader.Next(&set)) {
    times.push_back(set.t);
    both += set.images[0].has_value() && set.images[1].has_value();
  }
  ASSERT_EQ(times.size(), 6u);  // the shorter source leaves its camera out of the last sets
  EXPECT_EQ(both, 4);
  EXPECT_NEAR(ToSeconds(times[5] - times[0]), 5.0 / 30, kMs);
  EXPECT_EQ(reader.loops(), 0);
}

TEST(FrameSetReader, ASlowCameraJoinsTheFastOnesFrameTakenWithIt) {
  // Triggered together at 60 and 120 fps: each 60 fps frame joins the set of the 120 fps frame
  // of its own time (not the one half its period before, which is within its own half period).
  const std::string slow = WriteClip("p4_fsr_60.mkv", 60, 5),
                    fast = WriteClip("p4_fsr_120.mkv", 120, 10);
  FrameSetReader reader({slow, fast});
  FrameSet set;
  int sets = 0, both = 0;
  while (reader.Next(&set)) {
    ++sets;
    ASSERT_TRUE(set.images[1].has_value());
    if (set.images[0]) {
      ++both;
      EXPECT_NEAR(ToSeconds(set.times[0] - set.times[1]), 0.0, kMs);
    }
  }
  EXPECT_EQ(sets, 10);
  EXPECT_EQ(both, 5);
}

TEST(FrameSetReader, CameraClocksPutEachFrameAtItsRigTime) {
  // b started recording 2.5 frames after a (a known offset): its frames are grouped with a's
  // nearest ones and each image keeps its own time.
  const std::string a = WriteClip("p4_fsr_ca.mkv", 30, 8), b = WriteClip("p4_fsr_cb.mkv", 30, 4);
  CameraClock late;
  late.time_offset_s = 2.4 / 30;
  late.has_offset = true;
  FrameSetReader reader({a, b}, false, {CameraClock{}, late});
  FrameSet set;
  std::vector<TimeNs> b_times;
  int sets = 0;
  while (reader.Next(&set)) {
    ++sets;
    ASSERT_EQ(set.times.size(), 2u);
    if (set.images[1]) {
      b_times.push_back(set.times[1]);
      EXPECT_TRUE(set.images[0].has_value());  // b's frame lies within half a period of a's
      EXPECT_NEAR(ToSeconds(set.times[1] - set.times[0]), 0.4 / 30, kMs);
    }
  }
  EXPECT_EQ(sets, 8);
  ASSERT_EQ(b_times.size(), 4u);
  EXPECT_NEAR(ToSeconds(b_times[0]), 2.4 / 30, kMs);
  // A wrong number of clocks is refused.
  EXPECT_THROW(FrameSetReader({a, b}, false, {late}), Error);
}

TEST(FrameSetReader, LoopPlaysTheFilesAgainWithTimeGoingOn) {
  const std::string a = WriteClip("p4_fsr_la.mkv", 30, 5), b = WriteClip("p4_fsr_lb.mkv", 30, 5);
  FrameSetReader reader({a, b}, /*loop=*/true);
  FrameSet set;
  std::vector<TimeNs> times;
  for (int k = 0; k < 17 && reader.Next(&set); ++k) {
    EXPECT_TRUE(set.images[0].has_value() && set.images[1].has_value()) << "set " << k;
    times.push_back(set.t);
  }
  ASSERT_EQ(times.size(), 17u);  // it does not end by itself
  for (std::size_t k = 1; k < times.size(); ++k) {
    // One frame period between every two sets, across the loops' seams too.
    EXPECT_NEAR(ToSeconds(times[k] - times[k - 1]), 1.0 / 30, kMs) << "set " << k;
  }
  EXPECT_EQ(reader.loops(), 3);
}

TEST(FrameSetReader, ALiveSourceCannotLoop) {
  try {
    FrameSetReader reader({"/dev/video97"}, /*loop=*/true);
    FAIL() << "a live source was accepted for a loop";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/video97"), std::string::npos) << e.what();
  }
}

// A network camera whose stream drops and comes back (here: a TCP stream served by FFmpeg, then a
// second served on the same port as soon as the first ends): the reader says it is lost, opens it
// again in the background, says it is back, and its frames go on with time still increasing.
// The test waits on what the reader says, not on a clock (the deadline only guards a hang).
TEST(FrameSetReader, ALiveSourceThatDropsIsOpenedAgain) {
  // H.264 in MPEG-TS, as a network camera sends.
  const std::string clip = WriteClip("p4_fsr_live.ts", 30, 45, 160, 120, VideoCodec::kH264);
  const int port = 20000 + (::getpid() + 7919) % 20000;
  const std::string url = "tcp://127.0.0.1:" + std::to_string(port);
  const std::string serve_once = "ffmpeg -v error -re -i " + clip + " -c copy -f mpegts '" + url +
                                 "?listen=1&listen_timeout=60000' > /dev/null 2>&1";
  // Two servers one after the other: the second listens as soon as the first has ended.
  ASSERT_EQ(std::system(("(" + serve_once + "; " + serve_once + ") &").c_str()), 0);
  std::atomic<bool> stop{false};
  FrameSetReaderOptions options;
  options.reconnect_min_s = 0.05;
  options.reconnect_max_s = 0.2;
  options.stop = &stop;
  std::unique_ptr<FrameSetReader> reader;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!reader && std::chrono::steady_clock::now() < deadline) {
    try {
      reader = std::make_unique<FrameSetReader>(std::vector<std::string>{url}, options);
    } catch (const Error&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ASSERT_TRUE(reader) << "could not connect to " << url;
  FrameSet set;
  int before = 0, after = 0;
  bool lost = false, back = false;
  TimeNs last = -1;
  while (after < 30 && std::chrono::steady_clock::now() < deadline && reader->Next(&set)) {
    for (const SourceEvent& e : reader->TakeSourceEvents()) {
      if (!e.back) {
        EXPECT_FALSE(lost) << "lost twice";
        lost = true;
      } else {
        EXPECT_TRUE(lost);
        EXPECT_GT(e.seconds_away, 0.0);
        back = true;
      }
    }
    ASSERT_TRUE(set.images[0].has_value());
    EXPECT_GT(set.t, last);
    if (back && last >= 0 && after == 0) {
      // The new stream's first frame comes after the old stream's last, by about the time away.
      EXPECT_GT(ToSeconds(set.t - last), 0.0);
    }
    last = set.t;
    (back ? after : before) += 1;
  }
  stop = true;
  EXPECT_TRUE(lost);
  EXPECT_TRUE(back);
  EXPECT_GE(before, 35);
  EXPECT_GE(after, 30);
  reader.reset();
  fs::remove(clip);
}

}  // namespace
}  // namespace p4
