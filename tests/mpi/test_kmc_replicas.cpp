// kmc replicas over 2, 3 or 4 ranks give bitwise the numbers of 1 rank: replica r is seeded from
// (seed, r) wherever it runs, and rank 0 reduces in replica order.
#include "narrows/engines/kmc/driver.hpp"
#include "narrows/models/three_state/rates.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

using namespace narrows;

TEST(KmcReplicas, RanksEqualOneRankBitwise) {
  scene::Kmc m;
  m.length = 40;
  using three_state::pair_code;
  m.rates[pair_code(1, 0) * 9 + pair_code(0, 1)] = 1.0;
  m.rates[pair_code(2, 0) * 9 + pair_code(0, 2)] = 0.7;
  m.rates[pair_code(1, 1) * 9 + pair_code(0, 2)] = 0.3;
  m.rates[pair_code(0, 2) * 9 + pair_code(1, 1)] = 0.4;
  m.left[0 * 3 + 1] = 0.5;
  m.left[0 * 3 + 2] = 0.2;
  m.right[1 * 3 + 0] = 0.6;
  m.right[2 * 3 + 0] = 0.9;
  m.initial = {0.5, 0.3, 0.2};
  m.time = 200.0;
  m.warmup = 20.0;
  m.replicas = 5; // uneven on 2, 3 and 4 ranks on purpose

  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  ASSERT_GE(ranks, 2);
  const auto both = kmc::run_replicas(m, 9, MPI_COMM_WORLD);
  const auto one = kmc::run_replicas(m, 9, MPI_COMM_SELF);
  EXPECT_EQ(both.events, one.events); // every rank knows the total
  if (rank == 0) {
    EXPECT_EQ(both.current, one.current);
    EXPECT_EQ(both.current_error, one.current_error);
    EXPECT_EQ(both.density, one.density);
    EXPECT_EQ(both.density_error, one.density_error);
    EXPECT_EQ(both.mean_current, one.mean_current);
    EXPECT_EQ(both.mean_current_error, one.mean_current_error);
    EXPECT_EQ(both.current_left, one.current_left);
    EXPECT_EQ(both.current_right, one.current_right);
    EXPECT_GT(both.mean_current_error, 0.0);
  }
}
