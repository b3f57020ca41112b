#include "p4/io/truth_files.h"

#include <fmt/format.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>

#include "p4/core/error.h"

namespace p4 {
namespace {

std::ofstream OpenOut(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot create the file");
  return out;
}

}  // namespace

void WriteTruthCsv(const std::string& path, const sim::Trajectory& trajectory, int fps,
                   int64_t frames) {
  std::ofstream out = OpenOut(path);
  out << "t,x,y,z,vx,vy,vz,wx,wy,wz,in_play\n";
  for (int64_t k = 0; k < frames; ++k) {
    const double t = static_cast<double>(k) / fps;
    const auto s = trajectory.At(t);
    if (!s) {
      out << fmt::format("{:.6f},,,,,,,,,,0\n", t);
      continue;
    }
    const auto& p = s->position;
    const auto& v = s->velocity;
    const auto& w = s->spin;
    out << fmt::format("{:.6f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.5f},{:.3f},{:.3f},{:.3f},1\n",
                       t, p.x(), p.y(), p.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z());
  }
  if (!out) throw Error(path + ": write failed");
}

void WriteVisibilityCsv(const std::string& path, const Rig& rig,
                        const std::vector<std::vector<float>>& visibility, int fps) {
  std::ofstream out = OpenOut(path);
  out << "t";
  for (const auto& c : rig.cameras) out << ',' << c.name;
  out << '\n';
  const std::size_t frames = visibility.empty() ? 0 : visibility[0].size();
  for (std::size_t k = 0; k < frames; ++k) {
    out << fmt::format("{:.6f}", static_cast<double>(k) / fps);
    for (const auto& camera : visibility) out << fmt::format(",{:.3f}", camera[k]);
    out << '\n';
  }
  if (!out) throw Error(path + ": write failed");
}

std::vector<std::vector<float>> ReadVisibilityCsv(const std::string& path, const Rig& rig) {
  std::ifstream in(path);
  if (!in) return {};
  std::string line;
  std::getline(in, line);
  std::string expected = "t";
  for (const auto& c : rig.cameras) expected += "," + c.name;
  if (line != expected) throw Error(path + ": line 1: expected '" + expected + "'");
  std::vector<std::vector<float>> rows;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    std::stringstream s(line);
    std::string cell;
    std::getline(s, cell, ',');
    std::vector<float> row;
    while (std::getline(s, cell, ',')) {
      try {
        row.push_back(std::stof(cell));
      } catch (const std::exception&) {
        throw Error(fmt::format("{}: line {}: '{}' is not a number", path, number, cell));
      }
    }
    if (static_cast<int>(row.size()) != rig.size()) {
      throw Error(fmt::format("{}: line {}: expected {} cameras", path, number, rig.size()));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

void WriteMarkerLayout(const std::string& path, const std::vector<sim::MarkerQuad>& markers,
                       const std::string& dictionary) {
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  if (!fs.isOpened()) throw Error(path + ": cannot create the file");
  fs << "dictionary" << dictionary;
  fs << "markers"
     << "[";
  for (const auto& m : markers) {
    cv::Mat corners(4, 3, CV_64F);
    for (int i = 0; i < 4; ++i) {
      for (int k = 0; k < 3; ++k) corners.at<double>(i, k) = m.corners[i][k];
    }
    fs << "{"
       << "id" << m.id << "corners" << corners << "}";
  }
  fs << "]";
}

}  // namespace p4

namespace p4 {

nlohmann::json LookToJson(const sim::Look& look) {
  const auto rgb = [](const sim::Rgb& c) { return nlohmann::json::array({c.r, c.g, c.b}); };
  nlohmann::json banners = nlohmann::json::array(), lamps = nlohmann::json::array();
  for (const sim::Banner& b : look.banners) {
    banners.push_back({{"wall", b.wall},
                       {"along", b.along},
                       {"z", b.z},
                       {"size", {b.width, b.height}},
                       {"color", rgb(b.color)},
                       {"lettering", rgb(b.lettering)}});
  }
  for (const sim::Lamp& l : look.lamps) {
    lamps.push_back({{"where", l.ceiling ? "ceiling" : "wall " + std::to_string(l.wall)},
                     {"centre", {l.centre.x(), l.centre.y()}},
                     {"size", {l.size.x(), l.size.y()}},
                     {"brightness", l.brightness}});
  }
  nlohmann::json j = {
      {"name", look.name},
      {"light", {look.light.x(), look.light.y(), look.light.z()}},
      {"ambient", look.ambient},
      {"ball_ambient", look.ball_ambient},
      {"ball_specular", look.ball_specular},
      {"white_balance", rgb(look.white_balance)},
      {"gain", look.gain},
      {"drift", look.drift},
      {"ball", rgb(look.ball)},
      {"white_ball", look.white_ball()},
      {"table", rgb(look.table)},
      {"floor", rgb(look.floor)},
      {"wall", rgb(look.wall)},
      {"barrier", rgb(look.barrier)},
      {"shirts", {rgb(look.shirt_a), rgb(look.shirt_b)}},
      {"shoes", rgb(look.shoes)},
      {"arm_swing", look.arm_swing},
      {"banners", banners},
      {"lamps", lamps},
  };
  if (look.spare_ball) {
    j["spare_ball"] = {look.spare_ball->x(), look.spare_ball->y(), look.spare_ball->z()};
  }
  return j;
}

}  // namespace p4
