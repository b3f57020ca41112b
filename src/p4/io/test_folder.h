// Tests of the file readers and writers: a fixture with a folder of its own under the system's
// temporary folder (named by the test's prefix and the process id), emptied after each test.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace p4::testing {

class TestFolder : public ::testing::Test {
 protected:
  explicit TestFolder(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / (prefix_ + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // The path of `name` in the folder.
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  // Writes `text` to `name` in the folder; returns its path.
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = Path(name);
    std::ofstream(path) << text;
    return path;
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace p4::testing
