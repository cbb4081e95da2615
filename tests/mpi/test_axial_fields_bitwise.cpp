// The observable axial_fields (engines/mpcd/axial_fields.hpp, Kanehl (thesis) eq 6.1) across
// ranks: polydisperse no-slip disks with spring contacts in a driven channel of 25 cells (uneven
// slabs on 2, 3 and 4 ranks), pushed along x across the slab edges. Every 40 steps the whole
// sample (phi, colloid velocity, fluid velocity per bin, each colloid's phi_i) on the ranks of
// the suite is bitwise that of one rank running the same scene; and at the end the channel mean
// of phi is the colloid area over the channel area.
#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/axial_fields.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

using namespace narrows;

namespace {

using narrows::testing::world_rank;
using narrows::testing::world_size;

scene::Scene channel_scene() {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = 3101;
  s.domain.size = {25, 12, 0};
  s.fluid.collision = scene::Collision::at_a;
  s.fluid.density = 6.0;
  s.fluid.dt = 0.1;
  s.fluid.sort_every = 7;
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.02, 0.0, 0.0}, 0};
  s.walls = scene::Walls{};
  scene::Colloids col;
  col.coupling = scene::ColloidCoupling::no_slip;
  col.contacts = scene::ColloidContacts::spring;
  col.spring = {2500.0, 2500.0, 0.5, 0.3, 10};
  col.radius = 1.3;
  col.radius_sd = 0.15;
  col.count = 14;
  col.placement = scene::ColloidPlacement::random;
  col.gravity = {0.02, 0.0, 0.0};
  s.colloids = col;
  s.text = "# axial fields across ranks\n";
  return s;
}

std::size_t differences(const std::vector<double> &a, const std::vector<double> &b) {
  if (a.size() != b.size())
    return std::max(a.size(), b.size()) + 1;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    n += std::memcmp(&a[i], &b[i], sizeof(double)) != 0;
  return n;
}

std::vector<mpcd::AxialSample> run(const scene::Scene &s, MPI_Comm comm, int steps, int every) {
  mpcd::MpcdSimulation sim(s, comm);
  const mpcd::AxialFields axial(sim.box(), 2.5); // 10 bins
  std::vector<mpcd::AxialSample> out;
  for (int i = 1; i <= steps; ++i) {
    sim.advance();
    if (i % every == 0)
      out.push_back(axial.sample(sim.gather_colloids(), sim.fluid(), comm));
  }
  return out;
}

} // namespace

TEST(AxialFieldsBitwise, SamplesEqualOneRank) {
  const scene::Scene s = channel_scene();
  const int steps = 200, every = 40;
  const auto par = run(s, MPI_COMM_WORLD, steps, every);
  if (world_rank() != 0)
    return;
  const auto ser = run(s, MPI_COMM_SELF, steps, every);
  ASSERT_EQ(par.size(), ser.size());
  for (std::size_t t = 0; t < par.size(); ++t) {
    EXPECT_EQ(par[t].phi.size(), 10u);
    EXPECT_EQ(differences(par[t].phi, ser[t].phi), 0u) << "sample " << t;
    EXPECT_EQ(differences(par[t].velocity, ser[t].velocity), 0u) << "sample " << t;
    EXPECT_EQ(differences(par[t].fluid_velocity, ser[t].fluid_velocity), 0u) << "sample " << t;
    EXPECT_EQ(differences(par[t].local_fraction, ser[t].local_fraction), 0u) << "sample " << t;
  }
  // The fields are not trivial: the fluid moves, and the channel mean of phi is the colloids'
  // area over the channel's.
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  const auto c = sim.gather_colloids();
  double area = 0.0;
  for (const double r : c.radius)
    area += colloids::colloid_volume(2, r);
  double mean = 0.0, flow = 0.0;
  for (std::size_t b = 0; b < par.back().phi.size(); ++b) {
    mean += par.back().phi[b] / 10.0;
    flow += par.back().fluid_velocity[b] / 10.0;
  }
  EXPECT_NEAR(mean, area / (25.0 * 12.0), 1e-12);
  EXPECT_GT(flow, 0.0);
  std::printf("%d ranks: %zu samples equal; channel mean phi %.6f, fluid velocity %.4f\n",
              world_size(), par.size(), mean, flow);
}
