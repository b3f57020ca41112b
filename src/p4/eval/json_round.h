// Figures in eval's JSON are rounded to a unit (0.001 for millimetres, 1e-5 for shares), so the
// output reads cleanly and compares between runs.
#pragma once

#include <cmath>

namespace p4 {

// x rounded to a multiple of `unit` (a power of ten below 1), without binary noise in the digits.
inline double RoundTo(double x, double unit) {
  return std::round(x / unit) / std::round(1.0 / unit);
}

}  // namespace p4
