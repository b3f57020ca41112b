// `p4track bench --quick`: the paper's grid is measured and reported (the figures themselves are
// for the README, not asserted here: the machines are shared).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "p4track_test_support.h"

namespace {

TEST(BenchCommand, ReportsThePapersGridAndTheOpenCvComparison) {
  namespace fs = std::filesystem;
  const fs::path out =
      fs::temp_directory_path() / ("p4_bench_" + std::to_string(::getpid()) + ".json");
  std::string log;
  ASSERT_EQ(p4::testing::P4track(
                "bench --quick --frames 8 --repeats 1 --no-decode --out " + out.string(), &log),
            0)
      << log;
  const auto report = nlohmann::json::parse(p4::testing::Slurp(out));
  fs::remove(out);
  EXPECT_FALSE(report["machine"]["cpu"].get<std::string>().empty());
  // 1-3 cameras x 320x240, 640x480 x ROI off/on, each with the paper's figure where it has one.
  ASSERT_EQ(report["loop"].size(), 12u);
  int with_paper = 0;
  for (const auto& row : report["loop"]) {
    EXPECT_GT(row["frame_sets_per_s"].get<double>(), 0.0);
    EXPECT_LE(row["latency_median_us"].get<double>(), row["latency_p99_us"].get<double>());
    with_paper += !row["paper_mps"].is_null();
  }
  EXPECT_EQ(with_paper, 10);  // the paper has no 3-camera 640x480 figures
  ASSERT_EQ(report["segmentation"].size(), 2u);
  for (const auto& s : report["segmentation"]) {
    EXPECT_GT(s["p4_full_frame_us"].get<double>(), 0.0);
    EXPECT_GT(s["opencv_full_frame_us"].get<double>(), 0.0);
  }
  EXPECT_NE(log.find("paper"), std::string::npos);
}

}  // namespace
