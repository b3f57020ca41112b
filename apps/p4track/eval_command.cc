// p4track eval: a tracking run's accuracy against the simulator's ground truth, as JSON.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/eval/evaluate.h"
#include "p4/eval/evaluate_events.h"
#include "p4/io/event_files.h"
#include "p4/io/rig_file.h"
#include "p4/io/run_files.h"
#include "p4/io/truth_files.h"

namespace p4::app {
namespace {

struct EvalArgs {
  std::string truth, run, out;
};

int Run(const EvalArgs& a) {
  namespace fs = std::filesystem;
  const Rig rig = ReadRig((fs::path(a.truth) / "rig.yaml").string());
  const auto truth = ReadTruthCsv((fs::path(a.truth) / "truth.csv").string());
  const auto run = ReadTrajectoryCsv((fs::path(a.run) / "trajectory.csv").string());
  const auto visibility =
      ReadVisibilityCsv((fs::path(a.truth) / "truth_visibility.csv").string(), rig);
  const EvalReport report = Evaluate(truth, run, rig, visibility);
  nlohmann::ordered_json json_report = report.ToJson();
  // The game layer, when the run has one (tracked without --no-referee).
  const fs::path run_events = fs::path(a.run) / "events.jsonl";
  if (fs::exists(run_events)) {
    const EventReport events =
        EvaluateEvents(ReadEventsJsonl((fs::path(a.truth) / "truth_events.jsonl").string()),
                       ReadEventsJsonl(run_events.string()));
    const nlohmann::ordered_json game = events.ToJson();
    for (const auto& [key, value] : game.items()) json_report[key] = value;
  }
  const std::string json = json_report.dump(2);
  std::cout << json << std::endl;
  if (!a.out.empty()) {
    std::ofstream out(a.out);
    if (!(out << json << '\n')) throw Error(a.out + ": cannot write the file");
  }
  return 0;
}

}  // namespace

std::function<int()> AddEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* cmd =
      app.add_subcommand("eval", "Accuracy of a tracking run against simulated truth (JSON)");
  cmd->add_option("--truth", args->truth, "Folder written by `p4track simulate`")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--run", args->run, "Folder written by `p4track track`")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", args->out, "Also write the JSON to this file");
  return [args]() { return Run(*args); };
}

}  // namespace p4::app
