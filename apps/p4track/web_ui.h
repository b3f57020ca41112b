// The web UI's parts shared by `track --ui` and `replay`: the server's flags, the warning for a
// non-loopback address, and Ctrl-C.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <string>

#include "p4/server/web_server.h"

namespace p4::app {

struct WebFlags {
  std::string bind = "127.0.0.1";
  int port = 8080;
  std::string web_dir = P4_WEB_DIR;

  void Add(CLI::App* cmd);
  server::WebServerOptions Options() const;
};

// Starts the server and logs its address (and a warning when it is reachable from the network).
void StartAndAnnounce(server::WebServer* server, const WebFlags& flags, const std::string& what);

// From now on SIGINT (Ctrl-C) and SIGTERM set the returned flag instead of ending the program;
// a second one ends it at once.
const std::atomic<bool>& CatchInterrupts();

// Blocks until SIGINT or SIGTERM (at once if one came already).
void WaitForInterrupt();

}  // namespace p4::app
