// The initial state is created where it lives: every rank makes only the particles of its own
// cell columns (none has to move before the first step, and the first step moves no more than
// the thin band at the slab edges that every step moves), and the state is bitwise the same on
// any number of ranks. Run on 2 ranks and on 3 (uneven slabs: 25 and 13 columns).
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/state_by_id.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstring>
#include <string>

using namespace narrows;

namespace {

struct Case {
  const char *name;
  int dim;
  bool walls = false;
  bool colloids = false;
  double radius_sd = 0.0;
};

scene::Scene make_scene(const Case &c) {
  scene::Scene s;
  s.run.dimensions = c.dim;
  s.run.seed = 57;
  s.domain.size = c.dim == 2 ? std::array<double, 3>{25, 10, 0} : std::array<double, 3>{13, 6, 6};
  s.fluid.collision = scene::Collision::srd;
  s.fluid.density = 7.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 120.0;
  if (c.walls)
    s.walls = scene::Walls{false, true, scene::VirtualFlow::rest};
  if (c.colloids) {
    scene::Colloids col;
    col.radius = c.dim == 2 ? 2.0 : 1.0;
    col.count = c.dim == 2 ? 5 : 4;
    col.placement = scene::ColloidPlacement::random;
    col.md_substeps = 50;
    col.radius_sd = c.radius_sd;
    s.colloids = col;
  }
  return s;
}

std::uint64_t sum(std::uint64_t v) {
  std::uint64_t all = 0;
  MPI_Allreduce(&v, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

class InitialState : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(InitialState, IsCreatedOnTheRankOwningItsCell) {
  const Case c = GetParam();
  const scene::Scene s = make_scene(c);
  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const auto &f = sim.fluid();
  const auto &slabs = sim.slabs();
  std::uint64_t outside = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const int column = static_cast<int>(std::floor(f.x[0][i]));
    outside +=
        column < slabs.first_column() || column >= slabs.first_column() + slabs.local_columns();
  }
  const std::uint64_t n = sum(f.size()), columns = sim.box().cells[0];
  EXPECT_EQ(n, mpcd::particle_count(s));
  // Before the first step, nothing is on a rank that does not own its cell.
  const std::uint64_t created_outside = sum(outside);
  EXPECT_EQ(created_outside, 0u) << "particles created outside their rank's slab";
  // The first step moves only the band at the slab edges (shift and one step of streaming,
  // at most about a column per edge), as any later step does.
  sim.advance();
  const std::uint64_t step0 = sum(sim.migrated_last_step());
  sim.advance();
  const std::uint64_t step1 = sum(sim.migrated_last_step());
  const auto ranks = static_cast<std::uint64_t>(slabs.ranks());
  EXPECT_LE(step0, 2 * ranks * n / columns) << "step 1 moved " << step1;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf("[ measured ] %s on %llu ranks: %llu particles, created outside their slab %llu, "
                "migrated in step 0: %llu, in step 1: %llu\n",
                c.name, static_cast<unsigned long long>(ranks), static_cast<unsigned long long>(n),
                static_cast<unsigned long long>(created_outside),
                static_cast<unsigned long long>(step0), static_cast<unsigned long long>(step1));
}

TEST_P(InitialState, IsTheSameOnAnyNumberOfRanks) {
  const Case c = GetParam();
  const scene::Scene s = make_scene(c);
  const auto total = mpcd::particle_count(s);
  mpcd::MpcdSimulation par(s, MPI_COMM_WORLD);
  const auto many = narrows::testing::state_by_id(par.fluid(), total, MPI_COMM_WORLD);
  // Each rank creates only the colloids of its own slab (nothing to migrate at the start).
  const auto &own = par.colloids();
  for (std::size_t a = 0; a < own.size(); ++a) {
    const int column = static_cast<int>(own.x[0][a]);
    EXPECT_EQ(par.slabs().owner(column), par.slabs().rank())
        << "colloid id " << own.id[a] << " at x = " << own.x[0][a] << " created off its slab";
  }
  const auto gathered = par.gather_colloids();
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0)
    return;
  mpcd::MpcdSimulation ser(s, MPI_COMM_SELF);
  const auto one = narrows::testing::state_by_id(ser.fluid(), total, MPI_COMM_SELF);
  ASSERT_EQ(one.size(), many.size());
  std::size_t differ = 0;
  for (std::size_t j = 0; j < one.size(); ++j)
    differ += std::memcmp(&one[j], &many[j], sizeof(double)) != 0;
  EXPECT_EQ(differ, 0u) << differ << " of " << one.size() << " numbers differ";
  const auto &ca = gathered, &cb = ser.colloids();
  ASSERT_EQ(ca.size(), cb.size());
  for (int k = 0; k < c.dim; ++k)
    for (std::size_t a = 0; a < ca.size(); ++a)
      EXPECT_EQ(std::memcmp(&ca.x[k][a], &cb.x[k][a], sizeof(double)), 0) << "colloid " << a;
}

INSTANTIATE_TEST_SUITE_P(Scenes, InitialState,
                         ::testing::Values(Case{"periodic2d", 2}, Case{"walls3d", 3, true},
                                           Case{"walls2d_colloids", 2, true, true},
                                           Case{"colloids2d_radius_sd", 2, false, true, 0.4},
                                           Case{"walls3d_colloids", 3, true, true}),
                         [](const auto &info) { return std::string(info.param.name); });
