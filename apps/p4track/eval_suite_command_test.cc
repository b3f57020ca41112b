// `p4track eval-suite`, its small CI form: two short scenes of the tuning set drawn from their
// seeds (a 3-camera sports rig in a random hall; a white ball in a random hall), simulated,
// tracked and evaluated by the suite itself. The full suite (24 checking scenes and more) is a
// benchmark whose figures are in the README.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "p4track_test_support.h"

namespace {

namespace fs = std::filesystem;

// One scene of a family's tuning set, simulated, tracked and evaluated by the suite in a folder
// of its own (`tag`); its entry of suite.json (the folder: *out, removed by the caller).
nlohmann::json OneScene(const std::string& family, int seed, const std::string& tag,
                        fs::path* out) {
  *out = fs::temp_directory_path() / ("p4_suite_" + tag + "_" + std::to_string(::getpid()));
  std::string log;
  EXPECT_EQ(
      p4::testing::P4track("eval-suite --out " + out->string() + " --family " + family +
                               " --set tuning --first " + std::to_string(seed) + " --scenes 1",
                           &log),
      0)
      << log;
  const auto suite = nlohmann::json::parse(p4::testing::Slurp(*out / "suite.json"));
  EXPECT_EQ(suite["scenes"].size(), 1u);
  return suite["scenes"].empty() ? nlohmann::json::object() : suite["scenes"][0];
}

TEST(EvalSuiteCommand, SimulatesTracksAndEvaluatesSeededScenes) {
  const fs::path out = fs::temp_directory_path() / ("p4_suite_" + std::to_string(::getpid()));
  std::string log;
  ASSERT_EQ(p4::testing::P4track(
                "eval-suite --out " + out.string() +
                    " --family sports,white --set tuning --first 2 --scenes 1 --findable",
                &log),
            0)
      << log;
  const auto suite = nlohmann::json::parse(p4::testing::Slurp(out / "suite.json"));
  ASSERT_EQ(suite["scenes"].size(), 2u);
  for (const auto& scene : suite["scenes"]) {
    ASSERT_TRUE(scene.contains("figures")) << scene.dump();
    EXPECT_EQ(scene["axes"]["seed"].get<int>(), 2);
    EXPECT_GT(scene["ball_px"].get<double>(), 4.0);
    // The videos are gone (the suite keeps only the truth, the run and the figures).
    EXPECT_FALSE(fs::exists(out / scene["scene"].get<std::string>() / "sim" / "cam0.mp4"));
    // --findable: the ball stands out at its true place in 2 cameras in every frame of these
    // scenes (measured 100 %; a camera 85-100 % of its own frames).
    ASSERT_TRUE(scene.contains("findable")) << scene.dump();
    const auto& findable = scene["findable"];
    EXPECT_GT(findable["frames_seen"].get<int>(), 100);
    EXPECT_GE(findable["share"].get<double>(), 0.98);
    ASSERT_EQ(findable["camera_found"].size(), findable["camera_seen"].size());
    for (std::size_t c = 0; c < findable["camera_seen"].size(); ++c) {
      EXPECT_LE(findable["camera_found"][c].get<int>(), findable["camera_seen"][c].get<int>());
      EXPECT_GE(findable["camera_found"][c].get<int>(),
                0.8 * findable["camera_seen"][c].get<int>());
      // What the whole-image finder also finds is a part of what the search finds.
      EXPECT_LE(findable["camera_started"][c].get<int>(), findable["camera_found"][c].get<int>());
    }
    EXPECT_LE(findable["frames_startable"].get<int>(), findable["frames_findable"].get<int>());
    EXPECT_NEAR(findable["startable_share"].get<double>(),
                findable["frames_startable"].get<double>() / findable["frames_seen"].get<int>(),
                1e-4);
  }
  const auto& sports = suite["scenes"][0]["figures"];
  EXPECT_LE(sports["position_rmse_mm"].get<double>(), 5.0);
  EXPECT_GE(sports["recall"].get<double>(), 0.99);
  EXPECT_LE(sports["false_positive_rate"].get<double>(), 0.005);
  // A white ball among white lines, lettering and lamps (measured 99.3 % recall, 2.4 mm, 0 %
  // false on this scene since both detectors look on the background; 83 % before).
  const auto& white = suite["scenes"][1]["figures"];
  EXPECT_GE(white["recall"].get<double>(), 0.95);
  EXPECT_LE(white["false_positive_rate"].get<double>(), 0.01);
  EXPECT_LE(white["position_rmse_mm"].get<double>(), 5.0);
  // The summary rows: one per family, with the target judged.
  ASSERT_EQ(suite["summary"].size(), 2u);
  EXPECT_TRUE(suite["summary"][0]["target_met"].is_boolean());
  // ...and the scenes meeting each of the family's targets, from their own figures (the white
  // family has no RMSE bound).
  const auto& sports_met = suite["summary"][0]["scenes_meeting"];
  EXPECT_EQ(sports_met["scenes"].get<int>(), 1);
  EXPECT_EQ(sports_met["all"].get<int>(), 1);
  const auto& white_met = suite["summary"][1]["scenes_meeting"];
  EXPECT_EQ(white_met["recall"].get<int>(), white["recall"].get<double>() >= 0.98 ? 1 : 0);
  EXPECT_EQ(white_met["false_positive_rate"].get<int>(), 1);
  EXPECT_FALSE(white_met.contains("rmse"));
  EXPECT_NE(p4::testing::Slurp(out / "suite.md").find("recall 1, FP 1, RMSE 1, all 1 of 1"),
            std::string::npos);
  EXPECT_NE(p4::testing::Slurp(out / "suite.md").find("| sports | tuning |"), std::string::npos);
  // The breakdown: each scene in one group per axis (its look known: the floor's hue too), and
  // each group of a family and set counting its one scene.
  for (const auto& scene : suite["scenes"]) {
    ASSERT_EQ(scene["groups"].size(), 6u) << scene.dump();
    for (const auto& group : scene["groups"]) {
      const auto& groups = suite["by_group"];
      const auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
        return g["family"] == scene["axes"]["family"] && g["group"] == group;
      });
      ASSERT_NE(it, groups.end()) << group;
      EXPECT_EQ((*it)["scenes_meeting"]["scenes"].get<int>(), 1);
    }
  }
  EXPECT_NE(p4::testing::Slurp(out / "suite.md").find("| family | set | group |"),
            std::string::npos);
  EXPECT_NE(p4::testing::Slurp(out / "suite.md").find("findable %"), std::string::npos);
  fs::remove_all(out);
}

// The default, --ball auto, on a yellow ball over a wooden floor that the default yellow classes
// take for the ball (tuning seed 3: 0 % recall with --ball yellow), with a banner and a shirt of
// the ball's own colour: the colour learnt from the scene tracks it (measured 95.2 % recall,
// median 0.85 mm, 0.23 % false rows whose error makes the RMSE 5.1 mm), and the learnt classes
// are saved with the run.
TEST(EvalSuiteCommand, BallAutoLearnsTheColourFromTheScene) {
  fs::path out;
  const nlohmann::json scene = OneScene("sports", 3, "auto", &out);
  ASSERT_TRUE(scene.contains("figures")) << scene.dump();
  EXPECT_EQ(scene["axes"]["ball"].get<std::string>(), "yellow");
  const auto& figures = scene["figures"];
  EXPECT_GE(figures["recall"].get<double>(), 0.9);
  EXPECT_LE(figures["false_positive_rate"].get<double>(), 0.01);
  EXPECT_LE(figures["position_median_mm"].get<double>(), 2.0);
  EXPECT_LE(figures["position_rmse_mm"].get<double>(), 10.0);
  EXPECT_TRUE(fs::exists(out / scene["scene"].get<std::string>() / "run" / "ball_classes.yaml"));
  fs::remove_all(out);
}

// One camera cannot learn the ball's colour (nothing tells the ball from what else moves), so it
// is chosen among named ones; in mono tuning seed 14 (an orange ball over a red-brown floor, its
// shaded side darker than the floor) the orange classes take 1 % of the ball's pixels and the
// floor's pieces, and the views measured 20-30 % short put the rows a metre off (1.5 % recall,
// 981 mm). The named colour's shades learnt from its own flights, outlined on the background,
// track it (measured 72.5 % recall, 59.9 mm; the one-camera smoother holds the rest) and are
// saved with the run.
TEST(EvalSuiteCommand, OneCameraLearnsTheNamedColoursShadesInThisHall) {
  fs::path out;
  const nlohmann::json scene = OneScene("mono", 14, "mono", &out);
  ASSERT_TRUE(scene.contains("figures")) << scene.dump();
  const auto& figures = scene["figures"];
  EXPECT_GE(figures["recall"].get<double>(), 0.6);
  EXPECT_LE(figures["position_rmse_mm"].get<double>(), 100.0);
  EXPECT_TRUE(fs::exists(out / scene["scene"].get<std::string>() / "run" / "ball_classes.yaml"));
  fs::remove_all(out);
}

// Sports tuning seed 14 (3 cameras at 960x540, 60 fps, a yellow ball lit from above): in one
// camera the ball's shaded half nears the background so closely that most of its edge fits fail
// and its centres lean 1-3 px to the lit side (rows a few mm high). Such a view takes the faint
// side its camera's other views agreed on, and its centre moves back by the width it lost
// (measured: median 2.97 -> 2.14 mm, RMSE 3.90 -> 3.04 mm).
TEST(EvalSuiteCommand, AViewWithoutItsOwnFaintSideTakesItsCamerasFromTheHallsLight) {
  fs::path out;
  const nlohmann::json scene = OneScene("sports", 14, "faint", &out);
  ASSERT_TRUE(scene.contains("figures")) << scene.dump();
  const auto& figures = scene["figures"];
  EXPECT_GE(figures["recall"].get<double>(), 0.99);
  EXPECT_LE(figures["position_median_mm"].get<double>(), 2.5);
  EXPECT_LE(figures["position_rmse_mm"].get<double>(), 3.5);
  fs::remove_all(out);
}

// Sports tuning seed 26 (2 cameras at 960x540, 60 fps, an orange ball over a red-brown floor):
// during the serve's toss one camera sees only the lit cap of the ball (3 px of a 12 px ball) in
// every other frame, so those sets have no whole pair and no tracklet point; once the flight is
// confirmed the smoothed flight on both sides of each such set places the other camera's view on
// its ray (measured: recall 97.6 -> 98.4 %, no false row; since short views are measured by the
// outline of the ball's size, 96.8 -> 98.0 %: the last serve's first two sets are no row).
TEST(EvalSuiteCommand, TheSetsInsideAConfirmedFlightWithNoWholePairBecomeRows) {
  fs::path out;
  const nlohmann::json scene = OneScene("sports", 26, "gaps", &out);
  ASSERT_TRUE(scene.contains("figures")) << scene.dump();
  const auto& figures = scene["figures"];
  EXPECT_GE(figures["recall"].get<double>(), 0.975);
  EXPECT_LE(figures["false_positive_rate"].get<double>(), 0.0);
  EXPECT_LE(figures["position_rmse_mm"].get<double>(), 6.5);
  fs::remove_all(out);
}

// --merge: suites run apart (here two written by hand: sports tuning 1 and 2, then 2 again)
// summarised as one, nothing run: each scene counted once (the later suite's), its groups from
// its seed and its look.json; a folder without a suite.json is named.
TEST(EvalSuiteCommand, SuitesRunApartAreSummarisedAsOne) {
  const fs::path root = fs::temp_directory_path() / ("p4_merge_" + std::to_string(::getpid()));
  const auto suite = [&](const std::string& name, int seed, double recall) {
    const fs::path dir = root / name;
    const std::string scene = "sports-tuning-" + std::to_string(seed);
    fs::create_directories(dir / scene / "sim");
    nlohmann::json row = {{"scene", scene},
                          {"axes", {{"family", "sports"}, {"set", "tuning"}, {"seed", seed}}},
                          {"ball_px", 8.0},
                          {"figures",
                           {{"position_rmse_mm", 2.0},
                            {"recall", recall},
                            {"false_positive_rate", 0.0},
                            {"measured_rows", 300}}}};
    std::ofstream(dir / "suite.json") << nlohmann::json{{"scenes", {row}}}.dump();
    // A red-brown floor under an orange ball.
    std::ofstream(dir / scene / "sim" / "look.json")
        << R"({"floor": [0.5, 0.2, 0.11], "ball": [0.98, 0.33, 0.06]})";
    return dir.string();
  };
  const std::string a = suite("a", 1, 0.995), b = suite("b", 2, 0.97), c = suite("c", 2, 1.0);
  std::string log;
  ASSERT_EQ(p4::testing::P4track(
                "eval-suite --out " + (root / "all").string() + " --merge " + a + " " + b + " " + c,
                &log),
            0)
      << log;
  const auto merged = nlohmann::json::parse(p4::testing::Slurp(root / "all" / "suite.json"));
  ASSERT_EQ(merged["scenes"].size(), 2u);  // seed 2 once: c's
  EXPECT_EQ(merged["scenes"][1]["figures"]["recall"].get<double>(), 1.0);
  const auto& met = merged["summary"][0]["scenes_meeting"];
  EXPECT_EQ(met["scenes"].get<int>(), 2);
  EXPECT_EQ(met["all"].get<int>(), 2);
  const auto& groups = merged["by_group"];
  const auto floor = std::find_if(groups.begin(), groups.end(), [](const auto& g) {
    return g["group"] == "floor of the ball's hue";
  });
  ASSERT_NE(floor, groups.end()) << groups.dump();
  EXPECT_EQ((*floor)["scenes_meeting"]["scenes"].get<int>(), 2);
  EXPECT_NE(log.find("in an earlier suite too"), std::string::npos) << log;
  // A folder that holds no suite.
  fs::create_directories(root / "empty");
  EXPECT_NE(p4::testing::P4track("eval-suite --out " + (root / "x").string() + " --merge " +
                                     (root / "empty").string(),
                                 &log),
            0);
  EXPECT_NE(log.find((root / "empty" / "suite.json").string()), std::string::npos) << log;
  fs::remove_all(root);
}

}  // namespace
