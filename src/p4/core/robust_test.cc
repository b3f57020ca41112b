#include "p4/core/robust.h"

#include <gtest/gtest.h>

#include <vector>

namespace p4 {
namespace {

TEST(Robust, MedianIsTheMiddleElementWhateverTheOrder) {
  EXPECT_EQ(Median(std::vector<int>{5, 1, 4, 2, 3}), 3);
  // An even count: the upper of the two middle elements (what sorting puts at size / 2).
  EXPECT_EQ(Median(std::vector<double>{4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_EQ(Median(std::vector<float>{7.0f}), 7.0f);
}

TEST(Robust, SigmaIgnoresOutliersAndMatchesANormalSpread) {
  // |v - 10|: 0, 1, 1, 2, 2, 500 -> median 2 (upper middle) -> 2.9652.
  std::vector<double> v{10.0, 11.0, 9.0, 12.0, 8.0, 510.0};
  const double centre = MedianInPlace(v);
  EXPECT_EQ(centre, 11.0);
  std::vector<double> w{10.0, 11.0, 9.0, 12.0, 8.0, 510.0};
  EXPECT_NEAR(RobustSigmaInPlace(w, 10.0), 1.4826 * 2.0, 1e-12);
  // The deviations replace the values.
  EXPECT_EQ(w.size(), 6u);
  for (double d : w) EXPECT_GE(d, 0.0);
}

}  // namespace
}  // namespace p4
