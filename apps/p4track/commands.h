// Subcommands of p4track. Each registers its options on the CLI11 app and returns the function
// that runs it (exit code). Errors at the edges surface as p4::Error and exit code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace p4::app {

std::function<int()> AddSimulateCommand(CLI::App& app);
std::function<int()> AddTrackCommand(CLI::App& app);
std::function<int()> AddEvalCommand(CLI::App& app);

}  // namespace p4::app
