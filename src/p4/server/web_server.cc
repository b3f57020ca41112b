#include "p4/server/web_server.h"

#include <httplib.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "p4/core/error.h"

namespace p4::server {
namespace {

std::string ContentType(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  return "application/octet-stream";
}

std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void NoStore(httplib::Response& res) { res.set_header("Cache-Control", "no-store"); }

}  // namespace

void YieldToTracking() {
  thread_local bool lowered = false;
  if (lowered) return;
  lowered = true;
  // Linux "nice" is per thread. The lowest level, not SCHED_IDLE: a browser on the same laptop
  // keeps the CPU busy, and idle-class threads would then never answer it.
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
}

namespace {}  // namespace

bool WebServerOptions::IsValid(std::string* error) const {
  if (port < 0 || port > 65535) {
    *error = "port must be 0-65535, got " + std::to_string(port);
    return false;
  }
  if (bind.empty() || web_root.empty() || threads < 2) {
    *error = "bind address and web root must be set, threads >= 2";
    return false;
  }
  return true;
}

bool WebServer::IsLoopback(const std::string& address) {
  return address == "127.0.0.1" || address == "localhost" || address == "::1" ||
         address.rfind("127.", 0) == 0;
}

WebServer::WebServer(const WebServerOptions& options)
    : options_(options), server_(std::make_unique<httplib::Server>()) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("web server: " + why);
  namespace fs = std::filesystem;
  const fs::path root(options.web_root);
  for (const char* needed : {"live.html", "replay.html", "vendor/three.module.js"}) {
    if (!fs::exists(root / needed)) {
      throw Error(options.web_root + ": the UI's " + needed +
                  " is missing (run scripts/setup.sh, which installs three.js with npm, then "
                  "build again)");
    }
  }
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const std::string rel = fs::relative(entry.path(), root).generic_string();
    files_[rel] = {ReadAll(entry.path()), ContentType(entry.path())};
  }
  // SO_REUSEADDR only: httplib's default also sets SO_REUSEPORT, which would let a second P4 on
  // the same port share it silently instead of failing.
  server_->set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<void*>(&yes), sizeof(yes));
  });
  const int threads = options.threads;
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_->set_pre_routing_handler([](const httplib::Request&, httplib::Response&) {
    YieldToTracking();
    return httplib::Server::HandlerResponse::Unhandled;
  });
  server_->Get(R"(/static/(.+))", [this](const httplib::Request& req, httplib::Response& res) {
    const auto it = files_.find(req.matches[1].str());
    if (it == files_.end()) {
      res.status = 404;
      res.set_content("not found", "text/plain");
      return;
    }
    res.set_content(it->second.content, it->second.type);
  });
  server_->Get("/", [this](const httplib::Request&, httplib::Response& res) {
    const auto it = files_.find(page_);
    if (page_.empty() || it == files_.end()) {
      res.status = 404;
      return;
    }
    res.set_content(it->second.content, it->second.type);
  });
}

WebServer::~WebServer() { Stop(); }

void WebServer::ServeLive(const LiveHub* hub) {
  page_ = "live.html";
  server_->Get("/api/live/config", [hub](const httplib::Request&, httplib::Response& res) {
    res.set_content(hub->Config(), "application/json");
  });
  server_->Get("/api/live/state", [hub](const httplib::Request&, httplib::Response& res) {
    NoStore(res);
    const auto state = hub->State();
    if (!state) {
      res.status = 204;
      return;
    }
    res.set_content(*state, "application/json");
  });
  server_->Get("/api/live/markers", [hub](const httplib::Request&, httplib::Response& res) {
    NoStore(res);
    res.set_content(*hub->Markers(), "application/json");
  });
  server_->Get(R"(/api/live/camera/(\d{1,2})\.jpg)",
               [hub](const httplib::Request& req, httplib::Response& res) {
                 NoStore(res);
                 const auto jpeg = hub->Jpeg(std::stoi(req.matches[1].str()));
                 if (!jpeg) {
                   res.status = 404;
                   return;
                 }
                 res.set_content(*jpeg, "image/jpeg");
               });
}

void WebServer::ServeRun(const std::string& run_dir) {
  page_ = "replay.html";
  namespace fs = std::filesystem;
  static const std::map<std::string, std::string> kRunFiles = {
      {"trajectory.csv", "text/csv"},
      {"events.jsonl", "application/x-ndjson"},
      {"score.json", "application/json"},
      {"detections.csv", "text/csv"}};
  const fs::path dir(run_dir);
  server_->Get("/api/run/info", [dir](const httplib::Request&, httplib::Response& res) {
    nlohmann::json info;
    info["name"] = fs::absolute(dir).filename().string();
    info["files"] = nlohmann::json::array();
    for (const auto& [name, type] : kRunFiles) {
      if (fs::exists(dir / name)) info["files"].push_back(name);
    }
    res.set_content(info.dump(), "application/json");
  });
  server_->Get(R"(/api/run/([a-z_]+\.(csv|jsonl|json)))",
               [dir](const httplib::Request& req, httplib::Response& res) {
                 const auto it = kRunFiles.find(req.matches[1].str());
                 if (it == kRunFiles.end() || !fs::exists(dir / it->first)) {
                   res.status = 404;
                   res.set_content("not found", "text/plain");
                   return;
                 }
                 res.set_content(ReadAll(dir / it->first), it->second);
               });
}

int WebServer::Start() {
  const int port = options_.port == 0
                       ? server_->bind_to_any_port(options_.bind)
                       : (server_->bind_to_port(options_.bind, options_.port) ? options_.port : -1);
  if (port <= 0) {
    throw Error("web server: cannot listen on " + options_.bind + ":" +
                std::to_string(options_.port) + " (in use? try --port 0 for any free port)");
  }
  port_ = port;
  thread_ = std::thread([this] { server_->listen_after_bind(); });
  // Serving before returning: a stop() before the thread is listening would be lost.
  for (int i = 0; i < 5000 && !server_->is_running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return port_;
}

void WebServer::Stop() {
  if (thread_.joinable()) {
    server_->stop();
    thread_.join();
  }
}

std::string WebServer::Url() const {
  const std::string host = options_.bind == "0.0.0.0" ? "127.0.0.1" : options_.bind;
  return "http://" + host + ":" + std::to_string(port_) + "/";
}

}  // namespace p4::server
