#include "p4/io/event_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"

namespace p4 {
namespace {

TEST(EventFiles, RoundTripAndErrors) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("p4_events_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  game::Event bounce;
  bounce.t = 1.25;
  bounce.type = "bounce";
  bounce.side = 'B';
  bounce.position = Eigen::Vector3d(0.61, -0.2, 0.0);
  bounce.confidence = 0.9;
  game::Event point;
  point.t = 2.0;
  point.type = "point";
  point.winner = 'A';
  point.reason = "double bounce";
  point.score = {3, 2};
  const std::string path = (dir / "events.jsonl").string();
  WriteEventsJsonl(path, {bounce, point});
  EXPECT_EQ(EventToJsonLine(point),
            "{\"t\":2.000000,\"type\":\"point\",\"winner\":\"A\",\"reason\":\"double bounce\","
            "\"score\":[3,2],\"games\":[0,0]}");
  const auto events = ReadEventsJsonl(path);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].side, 'B');
  EXPECT_NEAR(events[0].position->x(), 0.61, 1e-9);
  EXPECT_NEAR(*events[0].confidence, 0.9, 1e-9);
  EXPECT_EQ(events[1].winner, 'A');
  EXPECT_EQ(events[1].score, (std::array<int, 2>{3, 2}));
  std::ofstream(dir / "bad.jsonl") << "{\"t\":1,\"type\":\"bounce\"}\n{\"t\":\n";
  try {
    ReadEventsJsonl((dir / "bad.jsonl").string());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.jsonl: line 2: not a JSON object"),
              std::string::npos);
  }
  // score.json names the players and is replaced whole.
  game::MatchScore score(3, 'B');
  score.AwardPoint('A');
  WriteJson((dir / "score.json").string(), ScoreToJson(score, 1, {"Ana", "Ben"}));
  std::ifstream in(dir / "score.json");
  const auto json = nlohmann::json::parse(in);
  EXPECT_EQ(json["players"][1].get<std::string>(), "Ben");
  EXPECT_EQ(json["score"][0].get<int>(), 1);
  EXPECT_EQ(json["best_of"].get<int>(), 3);
  EXPECT_FALSE(std::filesystem::exists(dir / ".tmp-score.json"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace p4
