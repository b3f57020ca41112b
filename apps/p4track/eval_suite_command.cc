// p4track eval-suite: many seeded worlds (halls, lights, balls, cameras) simulated, tracked and
// evaluated, with the worst scene reported beside the median (README "Measured on many worlds").
// Each scene runs `p4track simulate`, `track` and `eval` as child processes of this program, so
// one scene that fails is reported and the suite goes on.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/core/time.h"
#include "p4/eval/findable.h"
#include "p4/eval/suite.h"
#include "p4/io/rig_file.h"
#include "p4/io/run_files.h"
#include "p4/io/truth_files.h"
#include "p4/io/video_reader.h"

namespace p4::app {
namespace {

namespace fs = std::filesystem;

struct SuiteArgs {
  std::string out;
  std::vector<std::string> families{"sports", "webcam", "white", "mono"};
  std::string set = "both";
  int scenes = 4;
  int first = 1;
  bool keep = false;
  std::string ball = "auto";
  std::string readout = "found";  // rolling shutter: found from the ball, or known (the rig's)
  std::vector<std::string> track_args;
  bool findable = false;           // each scene's findable share (eval/findable.h), from its videos
  std::vector<std::string> merge;  // suites already run: summarised as one, nothing run
};

// Whether a scene's look (its sim/look.json) has a floor of the ball's hue; empty when the look
// does not give both colours.
std::optional<bool> FloorHueOf(const nlohmann::json& look) {
  const auto rgb = [&](const char* key) -> std::optional<Eigen::Vector3d> {
    const auto& c = look.is_object() && look.contains(key) ? look[key] : nlohmann::json();
    if (!c.is_array() || c.size() != 3 || !c[0].is_number() || !c[1].is_number() ||
        !c[2].is_number()) {
      return std::nullopt;
    }
    return Eigen::Vector3d(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
  };
  const auto floor = rgb("floor"), ball = rgb("ball");
  if (!floor || !ball) return std::nullopt;
  return FloorHasBallsHue(*floor, *ball);
}

// Runs this program with `args`, its output into `log`; the exit code (-1 when it did not run).
int RunSelf(const std::vector<std::string>& args, const std::string& log) {
  std::vector<std::string> all = {"p4track"};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(all.size() + 1);
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    FILE* f = std::freopen(log.c_str(), "a", stdout);
    if (f != nullptr) dup2(fileno(stdout), STDERR_FILENO);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// RMSE of a scene with no measured row, or of none: no figure ("-"), the worst there is.
constexpr double kNone = 1e9;

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  if (v.size() % 2) return v[v.size() / 2];
  const double a = v[v.size() / 2 - 1], b = v[v.size() / 2];
  return b >= kNone ? b : 0.5 * (a + b);  // with a scene of no figure in the middle: none
}

std::string Figure(const nlohmann::json& j, const char* key, double scale, int digits) {
  if (!j.contains(key) || !j[key].is_number()) return "-";
  return fmt::format("{:.{}f}", j[key].get<double>() * scale, digits);
}

bool Measured(const nlohmann::json& row) {
  return row.contains("figures") && row["figures"].value("measured_rows", 0) > 0;
}

std::string Mm(double v) { return v >= kNone ? "-" : fmt::format("{:.2f}", v); }

// One simulated, tracked and evaluated scene (the suite's scene or its twin).
// NOLINTNEXTLINE(bugprone-exception-escape): json's defaults analyse as throwing, never do.
struct Outcome {
  std::string failed;  // the step that failed, empty when all ran
  nlohmann::json figures;
  double ball_px = -1.0;
  nlohmann::json look;
  std::optional<bool> floor_of_balls_hue;  // from the look (FloorHueOf)
  double sync_ms = -1.0;  // the worst camera's clock error (kNone: refused; < 0: in step)
  std::optional<FindableReport> findable;
};

// The share of frames whose ball the streak search finds at its true place (eval/findable.h),
// read from the scene's videos. Cameras in step only (the truth's stamps are the frames').
FindableReport Findable(const SuiteScene& scene, const fs::path& sim) {
  const Rig rig = ReadRig((sim / "rig.yaml").string());
  segment::BallColour ball;
  segment::BallColour::Named(scene.ball, &ball);
  FindableCounter counter(rig, ReadTruthCsv((sim / "truth.csv").string()),
                          ReadVisibilityCsv((sim / "truth_visibility.csv").string(), rig), ball,
                          1e-3 * scene.exposure_ms);
  for (int c = 0; c < rig.size(); ++c) {
    VideoReader reader((sim / fmt::format("cam{}.mp4", c)).string());
    I420Image frame;
    TimeNs pts = 0;
    while (reader.Read(&frame, &pts)) counter.Add(c, pts, frame.View());
  }
  return counter.Report();
}

// The worst camera's clock error (ms) at the middle of the play: the clocks `track` found
// (run/rig_synced.yaml) against the simulator's (sim/rig_synced.yaml). < 0 when the cameras
// were in step, kNone when none was found.
double SyncErrorMs(const fs::path& sim, const fs::path& run, double seconds) {
  if (!fs::exists(sim / "rig_synced.yaml")) return -1.0;
  if (!fs::exists(run / "rig_synced.yaml")) return kNone;
  const Rig truth = ReadRig((sim / "rig_synced.yaml").string());
  const Rig found = ReadRig((run / "rig_synced.yaml").string());
  if (found.size() != truth.size()) return kNone;
  const TimeNs middle = FromSeconds(0.5 * seconds);
  // Each camera's error at its picture's middle row (a rolling shutter's line time found a
  // little off is traded against the offset: the rows the ball is seen on are what the fit
  // makes agree); the worst camera's against the reference's.
  const auto error = [&](int c) {
    const CameraClock &t = truth.cameras[c].clock, &f = found.cameras[c].clock;
    const double row = 0.5 * (truth.cameras[c].height - 1);
    const TimeNs stamp = t.Stamp(middle);
    return ToSeconds(f.WorldTime(stamp) - t.WorldTime(stamp)) + f.clock_rate * f.RowDelay(row) -
           t.clock_rate * t.RowDelay(row);
  };
  double worst = 0.0;
  for (int c = 1; c < truth.size(); ++c) {
    worst = std::max(worst, std::abs(error(c) - error(0)) * 1e3);
  }
  return worst;
}

// Simulates `scene` into dir/<prefix>sim, tracks it into dir/<prefix>run (with `track_args`
// after the suite's own) and evaluates it. A rolling-shutter scene's line times are found from
// the ball with the offsets (`track --rolling-shutter`), or with --readout known given in the rig
// (as from the phone's specification; the offsets still unknown). With `true_clocks`, the rig
// is the simulator's with its clocks (as a triggered rig's is known: no search).
Outcome SimulateTrackEvaluate(const SuiteScene& scene, const fs::path& dir,
                              const std::string& prefix, const SuiteArgs& a,
                              const std::vector<std::string>& track_args, bool true_clocks) {
  Outcome out;
  const std::string log = (dir / "log.txt").string();
  const fs::path sim = dir / (prefix + "sim"), run = dir / (prefix + "run");
  const std::string eval_file = (dir / (prefix + "eval.json")).string();
  std::vector<std::string> simulate = scene.SimulateArgs();
  simulate.insert(simulate.end(), {"--out", sim.string()});
  if (RunSelf(simulate, log) != 0) {
    out.failed = "simulate";
    return out;
  }
  std::string rig = (sim / "rig.yaml").string();
  if (true_clocks && fs::exists(sim / "rig_synced.yaml")) rig = (sim / "rig_synced.yaml").string();
  const bool rolling = !scene.rolling_shutter_ms.empty();
  if (rolling && a.readout == "known") {
    Rig readout = ReadRig(rig);
    const Rig truth = ReadRig((sim / "rig_synced.yaml").string());
    for (int c = 0; c < readout.size(); ++c) {
      readout.cameras[c].clock.line_time_s = truth.cameras[c].clock.line_time_s;
    }
    rig = (dir / (prefix + "rig_readout.yaml")).string();
    WriteRig(readout, rig);
  }
  out.ball_px = BallPixels(ReadRig(rig), ReadTruthCsv((sim / "truth.csv").string()));
  std::ifstream look_file(sim / "look.json");
  const auto look = nlohmann::json::parse(look_file, nullptr, false);
  if (!look.is_discarded()) {
    out.look = {{"banners", look["banners"].size()},
                {"lamps", look["lamps"].size()},
                {"spare_ball", look.contains("spare_ball")},
                {"drift", look["drift"]}};
    out.floor_of_balls_hue = FloorHueOf(look);
    if (out.floor_of_balls_hue) out.look["floor_of_balls_hue"] = *out.floor_of_balls_hue;
  }
  std::vector<std::string> track = {"track",
                                    "--rig",
                                    rig,
                                    "--out",
                                    run.string(),
                                    "--ball",
                                    a.ball == "auto" ? "auto" : scene.TrackBall()};
  track.insert(track.end(), a.track_args.begin(), a.track_args.end());
  track.insert(track.end(), track_args.begin(), track_args.end());
  if (rolling && a.readout == "found") track.push_back("--rolling-shutter");
  for (int c = 0; c < scene.cameras; ++c) {
    track.push_back((sim / fmt::format("cam{}.mp4", c)).string());
  }
  if (RunSelf(track, log) != 0) {
    out.failed = "track";
  } else if (RunSelf({"eval", "--truth", sim.string(), "--run", run.string(), "--out", eval_file},
                     log) != 0) {
    out.failed = "eval";
  } else {
    std::ifstream in(eval_file);
    out.figures = nlohmann::json::parse(in, nullptr, false);
    if (out.figures.is_discarded()) out.failed = "eval output";
    out.sync_ms = SyncErrorMs(sim, run, scene.seconds);
    if (a.findable && scene.start_offsets_s.empty()) {
      try {
        out.findable = Findable(scene, sim);
      } catch (const Error& e) {
        spdlog::warn("{}: no findable share: {}", sim.string(), e.what());
      }
    }
  }
  if (!a.keep) {
    std::error_code ec;
    for (int c = 0; c < scene.cameras; ++c) fs::remove(sim / fmt::format("cam{}.mp4", c), ec);
  }
  return out;
}

// Per family and set (in the order given): the worst scene and the median, against the family's
// target; and the scenes meeting each target, also by group (each row's "groups").
struct Summary {
  nlohmann::ordered_json summary = nlohmann::ordered_json::array();
  nlohmann::ordered_json by_group = nlohmann::ordered_json::array();
  std::string report;  // markdown: the summary table, then the groups' table
};

Summary Summarize(const nlohmann::ordered_json& results, const std::vector<std::string>& families,
                  const std::vector<std::string>& sets) {
  Summary out;
  nlohmann::ordered_json& summary = out.summary;
  nlohmann::ordered_json& groups_json = out.by_group;
  std::string group_report =
      "\n| family | set | group | scenes meeting each target |\n| --- | --- | --- | --- |\n";
  std::string report =
      "\n| family | set | scenes | RMSE mm worst / median | recall % worst / median | FP % worst / "
      "median | sync ms worst / median | RMSE / twin's worst | scenes meeting each target | "
      "target |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& family : families) {
    for (const auto& set : sets) {
      std::vector<double> rmse, recall, fp, sync, ratio;
      int failed = 0;
      const SuiteTarget target = TargetOf(family);
      TargetCounts counts;
      // Groups in the order of SceneGroups' axes, and by value within an axis ("under" first).
      using GroupKey = std::tuple<std::size_t, double, std::string>;
      std::map<GroupKey, TargetCounts> by_group;
      const auto key = [](const nlohmann::json& groups, std::size_t axis) -> GroupKey {
        const std::string name = groups[axis].get<std::string>();
        const auto digit = name.find_first_of("0123456789");
        const double value = name.find(" under ") != std::string::npos ? -1.0
                             : digit == std::string::npos              ? 0.0
                                                          : std::atof(name.c_str() + digit);
        return {axis, value, name};
      };
      for (const auto& row : results) {
        if (row["axes"]["family"] != family || row["axes"]["set"] != set) continue;
        const nlohmann::json groups =
            row.contains("groups") ? nlohmann::json(row["groups"]) : nlohmann::json::array();
        SceneFigures scene;  // a scene that failed before its figures meets no target
        if (!row.contains("figures")) {
          ++failed;
        } else {
          // A scene without a measured row has no error to show: it counts as the worst.
          const double r = Measured(row) ? row["figures"].value("position_rmse_mm", kNone) : kNone;
          rmse.push_back(r);
          recall.push_back(row["figures"].value("recall", 0.0));
          fp.push_back(row["figures"].value("false_positive_rate", 1.0));
          const auto known = [](double v) { return v >= kNone ? std::nullopt : std::optional(v); };
          scene.evaluated = true;
          scene.rmse_mm = known(r);
          scene.recall = recall.back();
          scene.false_positive_rate = fp.back();
          if (row.contains("sync_ms")) {
            sync.push_back(row["sync_ms"].is_null() ? kNone : row["sync_ms"].get<double>());
            scene.sync_ms = known(sync.back());
          }
          if (row.contains("twin")) {
            const auto& twin = row["twin"];
            const double t = twin.contains("figures") && Measured(twin)
                                 ? twin["figures"].value("position_rmse_mm", kNone)
                                 : kNone;
            ratio.push_back(r >= kNone || t >= kNone || t <= 0.0 ? kNone : r / t);
            scene.twin_ratio = known(ratio.back());
          }
        }
        CountTargetsMet(target, scene, &counts);
        for (std::size_t g = 0; g < groups.size(); ++g) {
          CountTargetsMet(target, scene, &by_group[key(groups, g)]);
        }
      }
      if (rmse.empty() && failed == 0) continue;
      for (const auto& [group_key, group_counts] : by_group) {
        const std::string& group = std::get<2>(group_key);
        group_report += fmt::format("| {} | {} | {} | {} |\n", family, set, group,
                                    group_counts.Describe(target));
        groups_json.push_back({{"family", family},
                               {"set", set},
                               {"group", group},
                               {"scenes_meeting", group_counts.ToJson(target)}});
      }
      const auto worst = [](const std::vector<double>& v, double none) {
        return v.empty() ? none : *std::max_element(v.begin(), v.end());
      };
      const double worst_rmse = worst(rmse, kNone);
      const double worst_recall =
          recall.empty() ? 0.0 : *std::min_element(recall.begin(), recall.end());
      const double worst_fp = worst(fp, 1.0);
      const double worst_sync = worst(sync, -1.0), worst_ratio = worst(ratio, -1.0);
      const bool met = failed == 0 && worst_recall >= target.min_recall &&
                       worst_fp <= target.max_fp && worst_rmse <= target.max_rmse_mm &&
                       Median(rmse) <= target.max_median_rmse_mm &&
                       worst_sync <= target.max_sync_ms && worst_ratio <= target.max_twin_ratio;
      nlohmann::ordered_json entry = {{"family", family},
                                      {"set", set},
                                      {"scenes", rmse.size()},
                                      {"failed", failed},
                                      {"rmse_mm_worst", worst_rmse},
                                      {"rmse_mm_median", Median(rmse)},
                                      {"recall_worst", worst_recall},
                                      {"recall_median", Median(recall)},
                                      {"fp_worst", worst_fp},
                                      {"fp_median", Median(fp)}};
      if (!sync.empty()) {
        entry["sync_ms_worst"] = worst_sync;
        entry["sync_ms_median"] = Median(sync);
      }
      if (!ratio.empty()) entry["twin_ratio_worst"] = worst_ratio;
      entry["scenes_meeting"] = counts.ToJson(target);
      entry["target_met"] = met;
      summary.push_back(entry);
      const auto ms = [](double v) {
        return v >= kNone ? std::string("refused") : fmt::format("{:.3f}", v);
      };
      report += fmt::format(
          "| {} | {} | {}{} | {} / {} | {:.1f} / {:.1f} | {:.2f} / {:.2f} | {} | {} | {} | {} |\n",
          family, set, rmse.size(), failed ? fmt::format(" ({} failed)", failed) : "",
          Mm(worst_rmse), Mm(Median(rmse)), 100.0 * worst_recall, 100.0 * Median(recall),
          100.0 * worst_fp, 100.0 * Median(fp),
          sync.empty() ? std::string("-") : ms(worst_sync) + " / " + ms(Median(sync)),
          ratio.empty()          ? std::string("-")
          : worst_ratio >= kNone ? std::string("-")
                                 : fmt::format("{:.2f}", worst_ratio),
          counts.Describe(target), met ? "met" : "missed");
    }
  }
  out.report = report + group_report;
  return out;
}

// --merge: the scenes of suites already run (each folder's suite.json), summarised as one into
// a.out; nothing is run. A scene in two of them is taken from the later. Rows written before the
// groups were counted get theirs from their seed and their folder's look.json.
int Merge(const SuiteArgs& a) {
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  std::vector<std::string> families, sets;
  const auto note = [](std::vector<std::string>* seen, const std::string& v) {
    if (std::find(seen->begin(), seen->end(), v) == seen->end()) seen->push_back(v);
  };
  for (const std::string& dir : a.merge) {
    const fs::path path = fs::path(dir) / "suite.json";
    std::ifstream file(path);
    if (!file) throw Error(path.string() + ": cannot read (not a folder eval-suite wrote?)");
    const auto suite = nlohmann::ordered_json::parse(file, nullptr, false);
    if (suite.is_discarded() || !suite.contains("scenes") || !suite["scenes"].is_array()) {
      throw Error(path.string() + ": not a suite's results (no \"scenes\" array)");
    }
    for (nlohmann::ordered_json row : suite["scenes"]) {
      if (!row.contains("axes") || !row.contains("scene") || !row["axes"].contains("family") ||
          !row["axes"].contains("set") || !row["axes"].contains("seed")) {
        throw Error(path.string() + ": a scene without its name or axes (family, set, seed)");
      }
      const std::string family = row["axes"]["family"], set = row["axes"]["set"];
      if (!row.contains("groups")) {
        const int seed = row["axes"]["seed"].get<int>();
        SuiteScene scene;
        try {
          scene = DrawSuiteScene(family, set, set == "checking" ? seed - 1000 : seed);
        } catch (const Error& e) {
          throw Error(path.string() + ": " + row["scene"].get<std::string>() + ": " + e.what());
        }
        std::ifstream look_file(fs::path(dir) / row["scene"].get<std::string>() / "sim" /
                                "look.json");
        const auto look = nlohmann::json::parse(look_file, nullptr, false);
        row["groups"] = SceneGroups(scene, row.value("ball_px", 0.0),
                                    look.is_discarded() ? std::nullopt : FloorHueOf(look));
      }
      const auto same = std::find_if(results.begin(), results.end(),
                                     [&](const auto& r) { return r["scene"] == row["scene"]; });
      if (same != results.end()) {
        spdlog::warn("{}: {} is in an earlier suite too; taking this one", path.string(),
                     row["scene"].get<std::string>());
        *same = row;
        continue;
      }
      note(&families, family), note(&sets, set);
      results.push_back(row);
    }
  }
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec) throw Error(a.out + ": cannot create the folder (" + ec.message() + ")");
  const Summary summed = Summarize(results, families, sets);
  std::cout << summed.report << std::flush;
  const nlohmann::ordered_json out = {{"scenes", results},
                                      {"summary", summed.summary},
                                      {"by_group", summed.by_group},
                                      {"merged_from", a.merge}};
  std::ofstream json_file(fs::path(a.out) / "suite.json");
  json_file << out.dump(2) << '\n';
  std::ofstream md_file(fs::path(a.out) / "suite.md");
  md_file << "Merged from " << fmt::format("{}", fmt::join(a.merge, ", ")) << "\n" << summed.report;
  if (!json_file || !md_file) throw Error(a.out + ": cannot write suite.json / suite.md");
  spdlog::info("{} scene(s) of {} suite(s) summarised; wrote {}/suite.json and suite.md",
               results.size(), a.merge.size(), a.out);
  return 0;
}

int Run(const SuiteArgs& a) {
  if (!a.merge.empty()) return Merge(a);
  const auto started = std::chrono::steady_clock::now();
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec) throw Error(a.out + ": cannot create the folder (" + ec.message() + ")");
  std::vector<std::string> sets;
  if (a.set == "both" || a.set == "tuning") sets.push_back("tuning");
  if (a.set == "both" || a.set == "checking") sets.push_back("checking");
  std::vector<SuiteScene> scenes;
  for (const auto& family : a.families) {
    for (const auto& set : sets) {
      for (int k = a.first; k < a.first + a.scenes; ++k) {
        scenes.push_back(DrawSuiteScene(family, set, k));
      }
    }
  }
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  std::string table =
      "| family | set | seed | cams | size | fps | exp ms | ball px | look | ball | RMSE mm | "
      "median mm | recall % | FP % | sync ms | twin RMSE mm / recall % |\n| --- | --- | --- | --- "
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::cout << table << std::flush;
  // --findable: per scene, the share of frames whose ball could be found at all (at its true
  // place), beside the recall.
  std::string findable_table =
      "\n| family | set | seed | findable % (>= 2 cameras) | startable % (>= 2 cameras) | recall % "
      "| per camera: found / seen (started) |\n| --- | --- | --- | --- | --- | --- | --- |\n";
  int index = 0;
  for (const SuiteScene& scene : scenes) {
    ++index;
    const std::string name = fmt::format("{}-{}-{}", scene.family, scene.set, scene.seed);
    const fs::path dir = fs::path(a.out) / name;
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir, ec);
    const std::string log = (dir / "log.txt").string();
    nlohmann::ordered_json row = {{"scene", name}, {"axes", scene.ToJson()}};
    const Outcome outcome = SimulateTrackEvaluate(scene, dir, "", a, {}, false);
    if (outcome.ball_px >= 0.0) row["ball_px"] = std::round(outcome.ball_px * 10.0) / 10.0;
    if (!outcome.look.is_null()) row["look"] = outcome.look;
    row["groups"] = SceneGroups(scene, std::max(0.0, outcome.ball_px), outcome.floor_of_balls_hue);
    if (outcome.findable) {
      const FindableReport& f = *outcome.findable;
      row["findable"] = {{"share", std::round(f.share() * 1e5) / 1e5},
                         {"frames_seen", f.frames_seen},
                         {"frames_findable", f.frames_findable},
                         {"startable_share", std::round(f.startable_share() * 1e5) / 1e5},
                         {"frames_startable", f.frames_startable},
                         {"camera_seen", f.camera_seen},
                         {"camera_found", f.camera_found},
                         {"camera_started", f.camera_started}};
      std::vector<std::string> cameras;
      for (std::size_t c = 0; c < f.camera_seen.size(); ++c) {
        cameras.push_back(
            fmt::format("{}/{} ({})", f.camera_found[c], f.camera_seen[c], f.camera_started[c]));
      }
      findable_table += fmt::format(
          "| {} | {} | {} | {:.1f} | {:.1f} | {} | {} |\n", scene.family, scene.set, scene.seed,
          100.0 * f.share(), 100.0 * f.startable_share(),
          outcome.failed.empty() ? Figure(outcome.figures, "recall", 100.0, 1) : std::string("-"),
          fmt::format("{}", fmt::join(cameras, " ")));
    }
    if (!outcome.failed.empty()) {
      row["failed"] = fmt::format("{} (see {})", outcome.failed, log);
      spdlog::warn("{}: {} failed, see {}", name, outcome.failed, log);
    } else {
      row["figures"] = outcome.figures;
      if (outcome.sync_ms >= 0.0) {
        row["sync_ms"] =
            outcome.sync_ms >= kNone ? nlohmann::json() : nlohmann::json(outcome.sync_ms);
      }
    }
    // The twin: the same play by cameras in step (tracked as triggered ones) or with a global
    // shutter (tracked as the scene is).
    std::string twin_cell = "-";
    if (!scene.twin.empty()) {
      const SuiteScene twin = scene.Twin();
      // In step: triggered together (the rates kept), the clocks known; the cameras at once.
      const bool in_step = scene.twin == "in-step";
      const Outcome t = SimulateTrackEvaluate(
          twin, dir, "twin-", a,
          in_step ? std::vector<std::string>{"--no-sync"} : std::vector<std::string>{}, in_step);
      if (!t.failed.empty()) {
        row["twin"] = {{"kind", scene.twin}, {"failed", t.failed}};
        twin_cell = "failed: " + t.failed;
      } else {
        row["twin"] = {{"kind", scene.twin}, {"figures", t.figures}};
        twin_cell =
            fmt::format("{} / {}",
                        Measured(row["twin"]) ? Figure(t.figures, "position_rmse_mm", 1.0, 2)
                                              : std::string("-"),
                        Figure(t.figures, "recall", 100.0, 1));
      }
    }
    const nlohmann::json& figures = outcome.figures;
    const std::string& failed = outcome.failed;
    const std::string line = fmt::format(
        "| {} | {} | {} | {} | {}x{} | {} | {:.1f} | {} | {} | {} | {} | {} | {} | {} | {} | {} "
        "|\n",
        scene.family, scene.set, scene.seed, scene.cameras, scene.width, scene.height, scene.fps,
        scene.exposure_ms,
        row.contains("ball_px") ? fmt::format("{:.1f}", row["ball_px"].get<double>()) : "-",
        scene.look, scene.ball,
        !failed.empty()  ? "failed: " + failed
        : !Measured(row) ? std::string("-")
                         : Figure(figures, "position_rmse_mm", 1.0, 2),
        Measured(row) ? Figure(figures, "position_median_mm", 1.0, 2) : "-",
        Figure(figures, "recall", 100.0, 1), Figure(figures, "false_positive_rate", 100.0, 2),
        !row.contains("sync_ms")   ? std::string("-")
        : row["sync_ms"].is_null() ? std::string("refused")
                                   : fmt::format("{:.3f}", row["sync_ms"].get<double>()),
        twin_cell);
    std::cout << line << std::flush;
    table += line;
    results.push_back(row);
    spdlog::debug("scene {}/{} done", index, scenes.size());
  }

  const Summary summed = Summarize(results, a.families, sets);
  std::string report = summed.report;
  if (a.findable) report += findable_table;
  std::cout << report << std::flush;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const nlohmann::ordered_json out = {{"scenes", results},
                                      {"summary", summed.summary},
                                      {"by_group", summed.by_group},
                                      {"seconds", seconds}};
  std::ofstream json_file(fs::path(a.out) / "suite.json");
  json_file << out.dump(2) << '\n';
  std::ofstream md_file(fs::path(a.out) / "suite.md");
  md_file << table << report;
  if (!json_file || !md_file) throw Error(a.out + ": cannot write suite.json / suite.md");
  spdlog::info("{} scene(s) in {:.0f} s; wrote {}/suite.json and suite.md", results.size(), seconds,
               a.out);
  return 0;
}

}  // namespace

std::function<int()> AddEvalSuiteCommand(CLI::App& app) {
  auto args = std::make_shared<SuiteArgs>();
  CLI::App* cmd = app.add_subcommand(
      "eval-suite",
      "Simulate, track and evaluate many seeded worlds (halls, lights, balls, cameras); print "
      "each scene and the worst and median per family");
  cmd->add_option("--out", args->out, "Folder for the scenes, suite.json and suite.md")->required();
  cmd->add_option("--family", args->families,
                  "Families of rigs: sports, webcam, white, mono; cameras out of step, each beside "
                  "its twin: unsync, unsync-webcam, phone (src/p4/eval/suite.h)")
      ->delimiter(',')
      ->check(CLI::IsMember(SuiteFamilies()))
      ->capture_default_str();
  cmd->add_option("--set", args->set,
                  "Seeds: tuning (1, 2, ...: choose parameters here), checking (1001, ...: only "
                  "measure), or both")
      ->check(CLI::IsMember({"tuning", "checking", "both"}))
      ->capture_default_str();
  cmd->add_option("--scenes", args->scenes, "Scenes per family and set")
      ->check(CLI::Range(1, 500))
      ->capture_default_str();
  cmd->add_option("--first", args->first, "First scene number of each set")
      ->check(CLI::Range(1, 499))
      ->capture_default_str();
  cmd->add_flag("--keep", args->keep, "Keep the rendered videos (deleted after each scene)");
  cmd->add_flag("--findable", args->findable,
                "Also measure each scene's findable share: the frames whose ball the streak search "
                "finds at its true place in 2 cameras or more (a ceiling for recall; cameras in "
                "step only), and the startable share: those the whole-image streak finder, with "
                "no prediction, also finds in 2 cameras or more");
  cmd->add_option("--ball", args->ball,
                  "auto: track as `track` does by default (--ball auto: the colour learnt from the "
                  "scene); hint: with the scene's ball colour named (--ball orange|white|yellow)")
      ->check(CLI::IsMember({"hint", "auto"}))
      ->capture_default_str();
  cmd->add_option("--readout", args->readout,
                  "Rolling-shutter scenes (phone): the line times found from the ball (track "
                  "--rolling-shutter) or known (the true ones in the rig, offsets unknown)")
      ->check(CLI::IsMember({"found", "known"}))
      ->capture_default_str();
  cmd->add_option("--track-args", args->track_args,
                  "Extra arguments for `p4track track`, e.g. --track-args=--no-roi")
      ->allow_extra_args(false);
  cmd->add_option("--merge", args->merge,
                  "Summarise suites already run (folders with a suite.json) as one into --out, "
                  "e.g. tuning 1-48 and 49-96 run apart; nothing is run again")
      ->check(CLI::ExistingDirectory);
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
