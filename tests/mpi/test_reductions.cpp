// Tests on 2, 3 and 4 ranks of what every rank must agree on without talking (grid shift) and
// of the reductions behind observables and invariant checks.
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

using namespace narrows;

namespace {

int rank() { return narrows::testing::world_rank(); }
int size() { return narrows::testing::world_size(); }

scene::Scene small_scene(int dim) {
  scene::Scene s;
  s.run.dimensions = dim;
  s.run.seed = 9;
  s.domain.size = {12.0, 8.0, dim == 3 ? 6.0 : 0.0};
  s.fluid.density = 7.0;
  s.fluid.dt = 0.5;
  return s;
}

// Keeps the particles of `f` whose index i satisfies i % ranks == rank, reversed, so each
// rank holds a share in an order unlike the serial one.
void keep_share(mpcd::Fluid &f) {
  mpcd::Fluid g;
  g.dim = f.dim;
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (static_cast<int>(i % size()) == rank())
      mine.push_back(i);
  std::reverse(mine.begin(), mine.end());
  g.resize(mine.size());
  for (std::size_t j = 0; j < mine.size(); ++j) {
    for (int k = 0; k < f.dim; ++k) {
      g.x[k][j] = f.x[k][mine[j]];
      g.v[k][j] = f.v[k][mine[j]];
    }
    g.id[j] = f.id[mine[j]];
  }
  f = std::move(g);
}

} // namespace

// ctest runs this binary on 2, 3 and 4 ranks and says so in NARROWS_TEST_RANKS: the run really
// has that many (an mpirun that quietly starts fewer would make the rank tests empty).
TEST(Ranks, RunsOnTheRanksCtestAskedFor) {
  const char *asked = std::getenv("NARROWS_TEST_RANKS");
  if (asked == nullptr)
    GTEST_SKIP() << "NARROWS_TEST_RANKS not set (run by hand)";
  EXPECT_EQ(size(), std::atoi(asked));
}

TEST(AnyRanks, GridShiftAgreesWithoutMessages) {
  for (std::uint64_t step : {0ull, 1ull, 77ull, 1ull << 33}) {
    const auto s = mpcd::grid_shift(42, step, 3);
    std::vector<double> all(3 * static_cast<std::size_t>(size()));
    MPI_Allgather(s.data(), 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, MPI_COMM_WORLD);
    for (int r = 1; r < size(); ++r)
      EXPECT_EQ(std::memcmp(all.data(), all.data() + 3 * r, 3 * sizeof(double)), 0)
          << "step " << step << " rank " << r;
  }
}

TEST(AnyRanks, MomentumSumIsBitwiseRankIndependent) {
  for (int dim : {2, 3}) {
    mpcd::MpcdSimulation serial(small_scene(dim), MPI_COMM_SELF);
    for (int i = 0; i < 5; ++i)
      serial.advance();
    const auto p1 = analysis::total_momentum(serial.fluid(), MPI_COMM_SELF);
    mpcd::Fluid shared = serial.fluid();
    keep_share(shared);
    const auto p2 = analysis::total_momentum(shared, MPI_COMM_WORLD);
    EXPECT_EQ(p1.count, p2.count);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(p1.fixed[k], p2.fixed[k]) << "dim " << dim << " axis " << k;
    const double t1 = analysis::temperature(serial.fluid(), MPI_COMM_SELF);
    const double t2 = analysis::temperature(shared, MPI_COMM_WORLD);
    EXPECT_NEAR(t1, t2, 1e-12 * t1);
  }
}

TEST(AnyRanks, InvariantCheckSeesAParticleLostOnOneRank) {
  mpcd::MpcdSimulation sim(small_scene(2), MPI_COMM_WORLD);
  // Each rank keeps its share: together they hold the whole fluid once.
  keep_share(sim.fluid());
  const mpcd::InvariantCheck check(sim);
  EXPECT_NO_THROW(check.check(sim));
  if (rank() == 1) { // lose one particle on rank 1 only
    auto &f = sim.fluid();
    const std::size_t n = f.size() - 1;
    for (int k = 0; k < f.dim; ++k) {
      f.x[k].resize(n);
      f.v[k].resize(n);
    }
    f.id.resize(n);
    f.cell.resize(n);
  }
  try {
    check.check(sim);
    ADD_FAILURE() << "lost particle not detected";
  } catch (const Error &e) {
    EXPECT_EQ(e.code(), ExitCode::invariant);
    EXPECT_NE(std::string(e.what()).find("particle count"), std::string::npos) << e.what();
  }
}
