// Tests only: damage a file in place, as a bad disk or a broken transfer would.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>

namespace p4::testing {

// Overwrites `count` bytes at `offset` with a fixed pseudo-random pattern (xorshift32).
inline void OverwriteWithNoise(const std::string& path, std::streamoff offset, int count) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(offset);
  uint32_t x = 2463534242u;
  for (int i = 0; i < count; ++i) {
    x ^= x << 13, x ^= x >> 17, x ^= x << 5;
    f.put(static_cast<char>(x & 0xff));
  }
}

}  // namespace p4::testing
