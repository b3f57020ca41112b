// Time in P4: int64 nanoseconds inside the program, seconds (double) in files (DESIGN.md).
#pragma once

#include <cmath>
#include <cstdint>

namespace p4 {

// Nanoseconds since the start of a recording (or of a live run).
using TimeNs = int64_t;

inline constexpr TimeNs kNanosPerSecond = 1'000'000'000;

inline constexpr double ToSeconds(TimeNs t) { return static_cast<double>(t) * 1e-9; }
inline TimeNs FromSeconds(double seconds) { return std::llround(seconds * 1e9); }

}  // namespace p4
