// P4's own web server (cpp-httplib): the UI's files and the data of a live run or a recorded one,
// read-only. It listens on 127.0.0.1 unless told otherwise; it serves only the files found in
// its web root at start (cached) and the run's own files by name — no path from a request ever
// reaches the file system.
//
//   GET /                         live.html (live) or replay.html (replay)
//   GET /static/<file>            the UI's files (html, js, css, vendored three.js)
//   GET /api/live/config|state|markers  LiveHub's JSON;  GET /api/live/camera/<i>.jpg  picture
//   GET /api/run/info             {"name", "files"};  GET /api/run/<file> trajectory.csv,
//                                 events.jsonl, score.json, detections.csv
#pragma once

#include <map>
#include <memory>
#include <string>
#include <thread>

#include "p4/server/live_hub.h"

namespace httplib {
class Server;
}

namespace p4::server {

// The UI's threads (HTTP workers, the picture encoder) call this once: they run at the lowest
// priority (nice 19, per thread), so tracking wins the CPU when it is short.
void YieldToTracking();

struct WebServerOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port
  std::string web_root;
  int threads = 64;  // connections served at once

  bool IsValid(std::string* error) const;
};

class WebServer {
 public:
  // Reads the web root; throws p4::Error when it lacks the UI's files (naming what is missing).
  explicit WebServer(const WebServerOptions& options);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  void ServeLive(const LiveHub* hub);
  void ServeRun(const std::string& run_dir);

  // Binds and serves in a thread; returns the port. Throws p4::Error when it cannot bind.
  int Start();
  void Stop();
  std::string Url() const;

  static bool IsLoopback(const std::string& address);

 private:
  struct File {
    std::string content, type;
  };
  WebServerOptions options_;
  std::map<std::string, File> files_;  // relative path -> content
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  int port_ = 0;
  std::string page_;
};

}  // namespace p4::server
