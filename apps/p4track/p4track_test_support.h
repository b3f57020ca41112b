// Helpers of the end-to-end tests that run the p4track program (P4TRACK_EXE) itself.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace p4::testing {

inline std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `p4track args`; returns its exit code and, if asked, what it printed (stdout + stderr).
inline int P4track(const std::string& args, std::string* output = nullptr) {
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() / ("p4track_log_" + std::to_string(::getpid()));
  const std::string command =
      std::string(P4TRACK_EXE) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  if (output) *output = Slurp(log);
  std::filesystem::remove(log);
  return WEXITSTATUS(status);
}

// Starts `p4track args` in the background (its output to `log`); returns its process id.
inline pid_t StartP4track(const std::string& args, const std::filesystem::path& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string command =
        "exec " + std::string(P4TRACK_EXE) + " " + args + " > " + log.string() + " 2>&1";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

// Lines in a file (0 when it is not there).
inline int CountLines(const std::filesystem::path& path) {
  std::ifstream in(path);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// `p4track eval` of a run against a simulation: its JSON report (a failed eval fails the test
// and its message does not parse).
inline nlohmann::json EvalReport(const std::filesystem::path& sim,
                                 const std::filesystem::path& run) {
  std::string out;
  EXPECT_EQ(P4track("eval --truth " + sim.string() + " --run " + run.string(), &out), 0) << out;
  return nlohmann::json::parse(out);
}

}  // namespace p4::testing
