// The simulator's ground truth on disk (DESIGN.md): truth.csv, truth_events.jsonl,
// truth_score.json, and markers.yaml for calibration scenes.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p4/game/match_score.h"
#include "p4/sim/match.h"
#include "p4/sim/scene.h"

namespace p4 {

// One row a frame, t = k / fps for k = 0 .. frames-1: t,x,y,z,vx,vy,vz,wx,wy,wz,in_play.
// Rows where the ball is not in the scene have in_play = 0 and empty state fields.
void WriteTruthCsv(const std::string& path, const sim::Trajectory& trajectory, int fps,
                   int64_t frames);

// One JSON object on one line, keys in DESIGN.md's order, numbers to the microsecond/micrometre.
std::string EventToJsonLine(const sim::TruthEvent& event);
void WriteEventsJsonl(const std::string& path, const std::vector<sim::TruthEvent>& events);

nlohmann::json ScoreToJson(const game::MatchScore& score, int points_played);
void WriteJson(const std::string& path, const nlohmann::json& json);

// markers.yaml: the dictionary name and, per marker, its id and 4 world corners (4x3, OpenCV
// corner order), as `p4track calibrate rig` reads it.
void WriteMarkerLayout(const std::string& path, const std::vector<sim::MarkerQuad>& markers,
                       const std::string& dictionary);

}  // namespace p4
