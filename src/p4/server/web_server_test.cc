#include "p4/server/web_server.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"

namespace p4::server {
namespace {

namespace fs = std::filesystem;

class WebServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("p4_web_" + std::to_string(getpid()));
    root_ = dir_ / "web";
    run_ = dir_ / "run";
    fs::create_directories(root_ / "vendor");
    fs::create_directories(run_);
    std::ofstream(root_ / "live.html") << "<html>live</html>";
    std::ofstream(root_ / "replay.html") << "<html>replay</html>";
    std::ofstream(root_ / "vendor/three.module.js") << "export const REVISION = '170';";
    std::ofstream(dir_ / "secret.txt") << "secret";
    std::ofstream(run_ / "trajectory.csv") << "t,x,y,z\n";
    std::ofstream(run_ / "notes.txt") << "private";
  }
  void TearDown() override { fs::remove_all(dir_); }
  WebServerOptions Options() const {
    WebServerOptions o;
    o.port = 0;
    o.web_root = root_.string();
    return o;
  }
  fs::path dir_, root_, run_;
};

TEST_F(WebServerTest, ServesTheReplayPageAndTheRunsFilesOnly) {
  WebServer server(Options());
  server.ServeRun(run_.string());
  const int port = server.Start();
  ASSERT_GT(port, 0);
  httplib::Client client("127.0.0.1", port);
  auto r = client.Get("/");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, "<html>replay</html>");
  r = client.Get("/static/vendor/three.module.js");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  r = client.Get("/api/run/trajectory.csv");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->body, "t,x,y,z\n");
  r = client.Get("/api/run/info");
  ASSERT_TRUE(r);
  EXPECT_NE(r->body.find("\"trajectory.csv\""), std::string::npos);
  // No way out of the web root or the run's named files.
  for (const char* path :
       {"/static/../secret.txt", "/static/%2e%2e/secret.txt", "/static/..%2fsecret.txt",
        "/static//etc/passwd", "/static/vendor/../../secret.txt", "/api/run/../secret.txt",
        "/api/run/%2e%2e%2fsecret.txt", "/api/run/notes.txt", "/api/run/score.json", "/secret.txt",
        "/../secret.txt", "/api/live/state"}) {
    r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_NE(r->status, 200) << path;
    EXPECT_EQ(r->body.find("secret"), std::string::npos) << path;
    EXPECT_EQ(r->body.find("private"), std::string::npos) << path;
  }
  // Read-only: nothing but GET.
  r = client.Post("/api/run/trajectory.csv", "x", "text/plain");
  ASSERT_TRUE(r);
  EXPECT_NE(r->status, 200);
  r = client.Delete("/api/run/trajectory.csv");
  ASSERT_TRUE(r);
  EXPECT_NE(r->status, 200);
  EXPECT_TRUE(fs::exists(run_ / "trajectory.csv"));
  server.Stop();
}

TEST_F(WebServerTest, SaysWhatIsMissingAndWhenThePortIsTaken) {
  fs::remove(root_ / "vendor/three.module.js");
  try {
    WebServer server(Options());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vendor/three.module.js is missing"), std::string::npos);
  }
  std::ofstream(root_ / "vendor/three.module.js") << "x";
  WebServer first(Options());
  first.ServeRun(run_.string());
  const int port = first.Start();
  WebServerOptions same = Options();
  same.port = port;
  WebServer second(same);
  try {
    second.Start();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:" + std::to_string(port)),
              std::string::npos);
  }
}

TEST(WebServer, LoopbackAddresses) {
  EXPECT_TRUE(WebServer::IsLoopback("127.0.0.1"));
  EXPECT_TRUE(WebServer::IsLoopback("localhost"));
  EXPECT_TRUE(WebServer::IsLoopback("::1"));
  EXPECT_FALSE(WebServer::IsLoopback("0.0.0.0"));
  EXPECT_FALSE(WebServer::IsLoopback("192.168.1.20"));
}

}  // namespace
}  // namespace p4::server
