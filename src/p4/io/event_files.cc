#include "p4/io/event_files.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"

namespace p4 {

std::string EventToJsonLine(const game::Event& e) {
  std::string line = fmt::format("{{\"t\":{:.6f},\"type\":\"{}\"", e.t, e.type);
  if (e.player) line += fmt::format(",\"player\":\"{}\"", e.player);
  if (e.side) line += fmt::format(",\"side\":\"{}\"", e.side);
  if (e.position) {
    line += fmt::format(",\"x\":{:.6f},\"y\":{:.6f},\"z\":{:.6f}", e.position->x(), e.position->y(),
                        e.position->z());
  }
  if (e.confidence) line += fmt::format(",\"confidence\":{:.3f}", *e.confidence);
  if (e.winner) {
    line += fmt::format(",\"winner\":\"{}\"", e.winner);
    if (!e.reason.empty()) line += fmt::format(",\"reason\":\"{}\"", e.reason);
    line += fmt::format(",\"score\":[{},{}],\"games\":[{},{}]", e.score[0], e.score[1], e.games[0],
                        e.games[1]);
  }
  return line + "}";
}

void WriteEventsJsonl(const std::string& path, const std::vector<game::Event>& events) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot create the file");
  for (const auto& e : events) out << EventToJsonLine(e) << '\n';
  if (!out) throw Error(path + ": write failed");
}

std::vector<game::Event> ReadEventsJsonl(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open");
  std::vector<game::Event> events;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = fmt::format("{}: line {}", path, number);
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::exception&) {
      if (in.eof()) break;  // a last line with no end: torn by a crash (io/line_appender.h)
      throw Error(where + ": not a JSON object");
    }
    try {
      game::Event e;
      e.t = j.at("t").get<double>();
      e.type = j.at("type").get<std::string>();
      const auto letter = [&](const char* key) -> char {
        if (!j.contains(key)) return 0;
        const std::string v = j[key].get<std::string>();
        if (v.size() != 1) throw Error(where + ": '" + key + "' must be one letter");
        return v[0];
      };
      e.player = letter("player");
      e.side = letter("side");
      e.winner = letter("winner");
      if (j.contains("x")) {
        e.position = Eigen::Vector3d(j.at("x").get<double>(), j.at("y").get<double>(),
                                     j.at("z").get<double>());
      }
      if (j.contains("confidence")) e.confidence = j["confidence"].get<double>();
      if (j.contains("reason")) e.reason = j["reason"].get<std::string>();
      if (j.contains("score")) e.score = j["score"].get<std::array<int, 2>>();
      if (j.contains("games")) e.games = j["games"].get<std::array<int, 2>>();
      events.push_back(std::move(e));
    } catch (const nlohmann::json::exception& ex) {
      throw Error(where + ": " + ex.what());
    }
  }
  return events;
}

nlohmann::json ScoreToJson(const game::MatchScore& score, int points_played,
                           const std::array<std::string, 2>& players) {
  nlohmann::json j;
  j["players"] = players;
  j["best_of"] = score.best_of();
  j["points_played"] = points_played;
  j["score"] = score.points();
  j["games"] = score.games();
  j["finished_games"] = score.finished_games();
  j["match_over"] = score.match_over();
  j["winner"] =
      score.match_over() ? nlohmann::json(std::string(1, score.match_winner())) : nlohmann::json();
  j["next_server"] = std::string(1, score.Server());
  return j;
}

void WriteJson(const std::string& path, const nlohmann::json& json) {
  const std::filesystem::path target(path);
  const std::filesystem::path temporary =
      target.parent_path() / (".tmp-" + target.filename().string());
  {
    std::ofstream out(temporary);
    if (!out) throw Error(path + ": cannot create the file");
    out << json.dump(2) << '\n';
    if (!out) throw Error(path + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, target, ec);
  if (ec) throw Error(path + ": cannot write the file (" + ec.message() + ")");
}

}  // namespace p4
