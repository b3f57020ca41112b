#include "web_ui.h"

#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

namespace p4::app {
namespace {

std::atomic<bool> g_interrupted{false};

// The first signal asks politely; a second one ends the program at once.
void OnSignal(int signal) {
  if (g_interrupted.exchange(true)) {
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

}  // namespace

void WebFlags::Add(CLI::App* cmd) {
  cmd->add_option("--port", port, "Port of the web UI (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--bind", bind,
                  "Address to listen on; anything but 127.0.0.1 exposes the UI to the network")
      ->capture_default_str();
  cmd->add_option("--web-dir", web_dir, "The UI's files (default: the build's)")
      ->check(CLI::ExistingDirectory);
}

server::WebServerOptions WebFlags::Options() const {
  server::WebServerOptions o;
  o.bind = bind;
  o.port = port;
  o.web_root = web_dir;
  return o;
}

void StartAndAnnounce(server::WebServer* server, const WebFlags& flags, const std::string& what) {
  server->Start();
  if (!server::WebServer::IsLoopback(flags.bind)) {
    spdlog::warn("the web UI listens on {}: anyone on the network can watch it (read-only)",
                 flags.bind);
  }
  spdlog::info("{}: {}", what, server->Url());
}

const std::atomic<bool>& CatchInterrupts() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  return g_interrupted;
}

void WaitForInterrupt() {
  const std::atomic<bool>& interrupted = CatchInterrupts();
  while (!interrupted) std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

}  // namespace p4::app
