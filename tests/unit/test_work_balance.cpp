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

TEST(WorkBalance, SharesGiveAFasterRankMoreWork) {
  // 12 columns of equal work; the second rank twice as fast: it takes 2/3 of the work.
  const std::vector<double> w(12, 1.0);
  EXPECT_EQ(balanced_first_columns(w, 2, 1, {1.0, 2.0}), (std::vector<int>{0, 4}));
  EXPECT_EQ(balanced_first_columns(w, 2, 1, {2.0, 1.0}), (std::vector<int>{0, 8}));
  // Equal shares: the same as none.
  EXPECT_EQ(balanced_first_columns(w, 3, 1, {5.0, 5.0, 5.0}), balanced_first_columns(w, 3));
  // 1 : 1 : 2 of 12: the boundaries at 3 and 6.
  EXPECT_EQ(balanced_first_columns(w, 3, 1, {1.0, 1.0, 2.0}), (std::vector<int>{0, 3, 6}));
  // A rank of share zero keeps the minimum width; the next boundary stays at half the total.
  EXPECT_EQ(balanced_first_columns(w, 3, 2, {0.0, 1.0, 1.0}), (std::vector<int>{0, 2, 6}));
  EXPECT_THROW(balanced_first_columns(w, 3, 1, {1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(balanced_first_columns(w, 2, 1, {0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(balanced_first_columns(w, 2, 1, {1.0, -1.0}), std::invalid_argument);
}

TEST(WorkBalance, SpeedSharesEvenTheBusyTime) {
  // Rank 0 did 100 units in 2 s, rank 1 100 in 1 s: rank 1 is twice as fast. Split 300 units by
  // these shares: rank 0 takes 100 (2 s at 50 per s), rank 1 200 (2 s at 100 per s).
  const std::vector<double> s = speed_shares({100.0, 100.0}, {2.0, 1.0});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s[0], 50.0);
  EXPECT_DOUBLE_EQ(s[1], 100.0);
  const std::vector<double> w(30, 10.0); // 300 units
  const std::vector<int> first = balanced_first_columns(w, 2, 1, s);
  EXPECT_EQ(first, (std::vector<int>{0, 10}));
  EXPECT_DOUBLE_EQ(10 * 10.0 / s[0], 20 * 10.0 / s[1]);
  // Nothing measured on a rank: equal shares (empty).
  EXPECT_TRUE(speed_shares({100.0, 0.0}, {1.0, 1.0}).empty());
  EXPECT_TRUE(speed_shares({100.0, 100.0}, {1.0, 0.0}).empty());
  EXPECT_THROW(speed_shares({1.0}, {1.0, 1.0}), std::invalid_argument);
}
