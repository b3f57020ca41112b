// Robust statistics of small samples: the median and the spread of a sample with outliers
// (1.4826 x the median absolute deviation: a normal distribution's sigma). Pure.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace p4 {

// The element that sorting would put at size / 2 (the upper of the two middle ones for an even
// count); reorders `values`. Precondition: `values` is not empty.
template <class T>
T MedianInPlace(std::vector<T>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// As MedianInPlace, on a copy.
template <class T>
T Median(std::vector<T> values) {
  return MedianInPlace(values);
}

// 1.4826 x the median of |value - centre| (MedianInPlace's middle); overwrites `values` with
// those deviations. Precondition: `values` is not empty.
template <class T>
double RobustSigmaInPlace(std::vector<T>& values, double centre) {
  for (T& v : values) v = static_cast<T>(std::abs(static_cast<double>(v) - centre));
  return 1.4826 * static_cast<double>(MedianInPlace(values));
}

}  // namespace p4
