// Subcommands of p4track. Each registers its options on the CLI11 app and returns the function
// that runs it (exit code). Errors at the edges surface as p4::Error and exit code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace p4::app {

std::function<int()> AddSimulateCommand(CLI::App& app);
std::function<int()> AddTrackCommand(CLI::App& app);
std::function<int()> AddEvalCommand(CLI::App& app);
std::function<int()> AddCalibrateCommand(CLI::App& app);
std::function<int()> AddReplayCommand(CLI::App& app);
std::function<int()> AddBenchCommand(CLI::App& app);
std::function<int()> AddEvalSuiteCommand(CLI::App& app);
std::function<int()> AddSyncCommand(CLI::App& app);

// "1280x720" -> width, height (even, 64x48 to 7680x4320); throws p4::Error naming `flag`.
void ParseSize(const std::string& text, const std::string& flag, int* width, int* height);

// --streaks auto|on|off as the highest frame rate whose cameras look for faint streaks: auto
// keeps `auto_fps`, on any rate, off none.
inline double StreakMaxFps(const std::string& streaks, double auto_fps) {
  return streaks == "on" ? 1e9 : streaks == "off" ? 0.0 : auto_fps;
}

}  // namespace p4::app
