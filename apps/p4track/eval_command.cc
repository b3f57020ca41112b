// p4track eval: a tracking run's accuracy against the simulator's ground truth, as JSON.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.h"
#include "p4/core/error.h"
#include "p4/eval/evaluate.h"
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
  const std::string json = report.ToJson();
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
