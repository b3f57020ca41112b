// Events and scores on disk (DESIGN.md): events.jsonl (one JSON object a line) and score.json,
// for the simulator's truth and the tracker's run alike.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p4/game/event.h"
#include "p4/game/match_score.h"

namespace p4 {

// One JSON object on one line, keys in DESIGN.md's order, numbers to the microsecond/micrometre.
std::string EventToJsonLine(const game::Event& event);
void WriteEventsJsonl(const std::string& path, const std::vector<game::Event>& events);

// Reads events.jsonl (blank lines skipped; a last line with no end that does not parse, torn by a
// crash, too). Throws p4::Error naming the file, line and field.
std::vector<game::Event> ReadEventsJsonl(const std::string& path);

// players: the names of A and B.
nlohmann::json ScoreToJson(const game::MatchScore& score, int points_played,
                           const std::array<std::string, 2>& players = {"A", "B"});
// Written atomically (a temporary file, then a rename): a reader never sees half a file.
void WriteJson(const std::string& path, const nlohmann::json& json);

}  // namespace p4
