// Slab boundaries balanced by work (work_balance.hpp): where the running sum crosses r/R of the
// total, each slab at least the minimum width; the imbalance figure max/mean.
#include "narrows/engines/mpcd/work_balance.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace narrows::mpcd;

TEST(WorkBalance, UniformWorkGivesEqualSlabs) {
  EXPECT_EQ(balanced_first_columns(std::vector<double>(12, 5.0), 3), (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(balanced_first_columns(std::vector<double>(12, 0.0), 4),
            (std::vector<int>{0, 3, 6, 9}));
}

TEST(WorkBalance, SlabsNarrowWhereTheWorkIs) {
  // Columns 0-3 hold 10 each, the other 8 columns 1 each: total 48, 24 per slab on 2 ranks.
  std::vector<double> w(12, 1.0);
  for (int c = 0; c < 4; ++c)
    w[c] = 10.0;
  EXPECT_EQ(balanced_first_columns(w, 2), (std::vector<int>{0, 2}));
  // 3 ranks, 16 each: the sum passes 10 at column 1, 20 at 2 (closer to 16), 40 at 4, 41 at 5,
  // ... 48 at 12; 32 lies between 30 (column 3) and 40 (column 4): 3.
  EXPECT_EQ(balanced_first_columns(w, 3), (std::vector<int>{0, 2, 3}));
}

TEST(WorkBalance, EverySlabKeepsTheMinimumWidth) {
  std::vector<double> w(10, 0.0);
  w[9] = 100.0; // all the work in the last column
  const std::vector<int> first = balanced_first_columns(w, 3, 2);
  EXPECT_EQ(first, (std::vector<int>{0, 6, 8}));
  for (std::size_t r = 0; r < first.size(); ++r)
    EXPECT_GE((r + 1 < first.size() ? first[r + 1] : 10) - first[r], 2) << "rank " << r;
  EXPECT_THROW(balanced_first_columns(w, 6, 2), std::invalid_argument);
}

TEST(WorkBalance, ImbalanceIsMaxOverMean) {
  EXPECT_DOUBLE_EQ(imbalance({1.0, 1.0, 1.0}), 1.0);
  EXPECT_DOUBLE_EQ(imbalance({3.0, 1.0, 2.0}), 1.5);
  EXPECT_DOUBLE_EQ(imbalance({0.0, 0.0}), 1.0);
}

TEST(WorkBalance, CountsWeighTheirCost) {
  WorkCounts a;
  a.fluid = 100.0;
  a.colloids = 2.0;
  WorkCounts b;
  b.bounces = 1.0;
  a += b;
  EXPECT_DOUBLE_EQ(a.work(),
                   100.0 * WorkWeights::fluid + 2.0 * WorkWeights::colloid + WorkWeights::bounce);
}
