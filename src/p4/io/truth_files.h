// The simulator's ground truth on disk (DESIGN.md): truth.csv, truth_events.jsonl,
// truth_score.json, and markers.yaml for calibration scenes.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p4/game/match_score.h"
#include "p4/geometry/rig.h"
#include "p4/io/event_files.h"
#include "p4/sim/match.h"
#include "p4/sim/scene.h"

namespace p4 {

// One row a frame, t = k / fps for k = 0 .. frames-1: t,x,y,z,vx,vy,vz,wx,wy,wz,in_play.
// Rows where the ball is not in the scene have in_play = 0 and empty state fields.
void WriteTruthCsv(const std::string& path, const sim::Trajectory& trajectory, int fps,
                   int64_t frames);

// truth_visibility.csv: t and, per camera (named by the rig), the share of the ball that camera
// sees in that frame (0: not in the picture or hidden; 1: fully seen).
void WriteVisibilityCsv(const std::string& path, const Rig& rig,
                        const std::vector<std::vector<float>>& visibility, int fps);
// Returns per frame and camera the share seen; empty when the file does not exist.
std::vector<std::vector<float>> ReadVisibilityCsv(const std::string& path, const Rig& rig);

// look.json: the hall's look of a simulated scene (light, colours, distractors), for reports.
nlohmann::json LookToJson(const sim::Look& look);

// markers.yaml: the dictionary name and, per marker, its id and 4 world corners (4x3, OpenCV
// corner order), as `p4track calibrate rig` reads it.
void WriteMarkerLayout(const std::string& path, const std::vector<sim::MarkerQuad>& markers,
                       const std::string& dictionary);

}  // namespace p4
