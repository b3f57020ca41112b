// Helpers of the libFuzzer targets (fuzz/README.md): the parsers read files, so each input is
// written to a file of this process first (in /dev/shm when it is there: no disk), and a parser
// may refuse it only with p4::Error — any other exception escapes and libFuzzer reports a crash.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace p4::fuzz {

// Writes the bytes to this process's file with the extension (".yaml", ".json", ".csv", ...);
// returns its path.
inline std::string WriteInput(const uint8_t* data, std::size_t size, std::string_view extension) {
  static const std::filesystem::path dir =
      std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
  const std::string path =
      (dir / ("p4_fuzz_" + std::to_string(::getpid()) + std::string(extension))).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace p4::fuzz
