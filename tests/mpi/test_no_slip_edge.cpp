// Issue 20 acceptance 6, the slab-edge hard case: no-slip colloids with hard contacts that span
// the slab edges at the start (one centred on the edge between the two slabs, one on the
// periodic edge x = 0, one touching it), in a channel under a pressure drive, 10^5 steps on 2
// ranks: the run's invariants every 100 steps, every colloid owned by exactly one rank, no
// overlap; the final state bitwise equal to one rank's.
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/state_by_id.hpp"
#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace narrows;

TEST(NoSlipHardCase, ColloidsSpanningTheSlabEdgesAtTheStart) {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = 17;
  s.domain.size = {24.0, 10.0, 0.0};
  s.fluid.collision = scene::Collision::at_a;
  s.fluid.density = 3.0;
  s.fluid.dt = 0.05;
  s.walls = scene::Walls{};
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.01, 0.0, 0.0}, 0.0};
  scene::Colloids c;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.contacts = scene::ColloidContacts::hard;
  c.radius = 2.0;
  c.count = 3;
  c.placement = scene::ColloidPlacement::list;
  c.positions = {{12.0, 5.0, 0.0}, {0.0, 3.0, 0.0}, {4.0, 3.0, 0.0}};
  c.gravity = {0.0, -0.01, 0.0};
  s.colloids = c;
  const char *env = std::getenv("NARROWS_EDGE_STEPS");
  const int steps = env ? std::atoi(env) : 100000;
  mpcd::MpcdSimulation par(s, MPI_COMM_WORLD);
  const mpcd::InvariantCheck invariants(par);
  for (int i = 1; i <= steps; ++i) {
    par.advance();
    if (i % 100 != 0)
      continue;
    ASSERT_NO_THROW(invariants.check(par)) << "step " << i;
    const auto all = par.gather_colloids();
    ASSERT_EQ(all.size(), 3u) << "step " << i;
    double gap = 1e9;
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = a + 1; b < 3; ++b) {
        double dx = all.x[0][a] - all.x[0][b];
        dx -= 24.0 * std::round(dx / 24.0);
        gap = std::min(gap, std::hypot(dx, all.x[1][a] - all.x[1][b]) - 4.0);
      }
    ASSERT_GT(gap, -1e-9) << "colloids overlap at step " << i;
  }
  const auto total = mpcd::particle_count(s);
  const auto mine = narrows::testing::state_by_id(par.fluid(), total, MPI_COMM_WORLD);
  const auto gathered = par.gather_colloids();
  if (narrows::testing::world_rank() != 0)
    return;
  mpcd::MpcdSimulation one(s, MPI_COMM_SELF);
  for (int i = 0; i < steps; ++i)
    one.advance();
  const auto ref = narrows::testing::state_by_id(one.fluid(), total, MPI_COMM_SELF);
  std::size_t differ = 0;
  for (std::size_t j = 0; j < ref.size(); ++j)
    differ += std::memcmp(&ref[j], &mine[j], sizeof(double)) != 0;
  for (int k = 0; k < 2; ++k)
    for (std::size_t a = 0; a < 3; ++a)
      differ += std::memcmp(&gathered.x[k][a], &one.colloids().x[k][a], sizeof(double)) != 0;
  std::printf("%d steps; %llu colloid collisions on rank 0; %zu numbers differ from one rank\n",
              steps, static_cast<unsigned long long>(par.no_slip()->contacts().pair_collisions),
              differ);
  EXPECT_EQ(differ, 0u);
}
