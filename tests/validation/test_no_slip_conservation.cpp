// Issue 20 acceptance 1: no-slip colloids (bounce-back, ghost particles, hard contacts) conserve
// the total momentum of fluid plus colloids to round-off over 10^4 steps for SRD, MPC-AT and
// MPC-AT+a; with MPC-AT+a the collision step with ghost particles also conserves the total
// angular momentum, fluid plus colloids (orbital X x M U and spin I Omega), with spinning
// colloids. (Streaming in a periodic box, and the bounce-back's move of a particle onto the
// surface, change the angular momentum by design: it is not a conserved quantity of the
// method, only of its collision.) The energy of hard-sphere collision sequences without fluid is
// tested in tests/unit/test_hard_spheres.cpp.
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/engines/mpcd/totals.hpp"

#include "colloid_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace narrows;

namespace {

scene::Scene no_slip_scene(scene::Collision rule) {
  scene::Colloids c;
  c.radius = 2.5;
  c.count = 3;
  c.placement = scene::ColloidPlacement::random;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.contacts = scene::ColloidContacts::hard;
  scene::Scene s = narrows::testing::srd_colloid_scene(24.0, 24.0, false, 12, c);
  s.fluid.collision = rule;
  s.fluid.angle_deg = 130.0;
  return s;
}

class NoSlipMomentum : public ::testing::TestWithParam<scene::Collision> {};

} // namespace

// 10^4 steps of 5300 particles and 3 colloids (about 4 s each).
TEST_P(NoSlipMomentum, TotalMomentumOverTenThousandSteps) {
  const scene::Scene s = no_slip_scene(GetParam());
  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const auto p0 = mpcd::total_momentum(sim);
  const int steps = 10000;
  double max_dp = 0.0, max_colloid_p = 0.0;
  for (int i = 1; i <= steps; ++i) {
    sim.advance();
    if (i % 50 == 0) {
      const auto p = mpcd::total_momentum(sim);
      const auto c = sim.gather_colloids();
      for (int k = 0; k < 2; ++k) {
        max_dp = std::max(max_dp, std::abs(p[k] - p0[k]));
        for (std::size_t a = 0; a < c.size(); ++a)
          max_colloid_p = std::max(max_colloid_p, std::abs(c.mass[a] * c.v[k][a]));
      }
    }
  }
  const double n = static_cast<double>(mpcd::particle_count(s));
  // Round-off: the cell sums are fixed point (each collision may move the total by N 2^-41 per
  // component; the invariant check allows twice N 2^-40 per step, as here); the impulses on the
  // colloids are fixed-point sums of the doubles the fluid particles change by, which differ by
  // at most 2^-41 per impulse (a few hundred bounces and ghosts per step: below N 2^-40).
  const double bound = 2.0 * n * 0x1p-40 * (steps + 1.0);
  const auto contacts = sim.no_slip()->contacts();
  std::printf("max |P - P0| = %.3g over %d steps (round-off bound %.3g), max |M U| = %.3g, "
              "%llu colloid collisions\n",
              max_dp, steps, bound, max_colloid_p,
              static_cast<unsigned long long>(contacts.pair_collisions));
  EXPECT_LT(max_dp, bound);
  // The colloids exchanged momentum with the fluid: the thermal momentum of one is
  // sqrt(M kT) = 14 (M = pi 2.5^2 10); far more than round-off.
  EXPECT_GT(max_colloid_p, 1.0);
}

INSTANTIATE_TEST_SUITE_P(Rules, NoSlipMomentum,
                         ::testing::Values(scene::Collision::srd, scene::Collision::at,
                                           scene::Collision::at_a),
                         [](const auto &info) {
                           return std::string(info.param == scene::Collision::srd  ? "srd"
                                              : info.param == scene::Collision::at ? "at"
                                                                                   : "at_a");
                         });

namespace {

// Total angular momentum about the origin (z) of fluid and colloids. A collision cell at the
// periodic edge holds particles near 0 and near L: each position is taken in [s, L + s) for the
// grid shift s, the image in which every cell is whole (the colloids lie far from the edges).
double angular_momentum(const mpcd::Fluid &f, const colloids::Colloids &c, const mpcd::CellGrid &g,
                        const mpcd::Box &box) {
  auto image = [&](double x, int k) {
    const double s = g.shift[k], L = box.length[k];
    return x < s ? x + L : (x >= L + s ? x - L : x);
  };
  double l = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i)
    l += image(f.x[0][i], 0) * f.v[1][i] - image(f.x[1][i], 1) * f.v[0][i];
  for (std::size_t a = 0; a < c.size(); ++a)
    l += c.mass[a] * (c.x[0][a] * c.v[1][a] - c.x[1][a] * c.v[0][a]) +
         colloids::moment_of_inertia(c, a) * c.omega[2][a];
  return l;
}

// Two colloids of radius 3 in a periodic 24 x 18 (x 12) box of MPC-AT+a fluid, no-slip.
scene::Scene two_colloids_scene(int dim) {
  scene::Colloids spec;
  spec.radius = 3.0;
  spec.count = 2;
  spec.placement = scene::ColloidPlacement::list;
  spec.positions = {{7.3, 8.1, dim == 3 ? 5.2 : 0.0}, {15.6, 9.4, dim == 3 ? 6.9 : 0.0}};
  spec.coupling = scene::ColloidCoupling::no_slip;
  scene::Scene s = narrows::testing::srd_colloid_scene(24.0, 18.0, false, 5, spec);
  s.fluid.collision = scene::Collision::at_a;
  s.run.dimensions = dim;
  if (dim == 3) {
    s.domain.size = {24.0, 18.0, 12.0};
    s.fluid.density = 5.0;
  }
  return s;
}

} // namespace

// The collision step alone: ghost particles of two spinning colloids join the MPC-AT+a
// collision, and their momentum and angular momentum change goes to the colloids.
TEST(NoSlipAngularMomentum, AtaCollisionWithGhostsConservesTheTotal) {
  const scene::Scene s = two_colloids_scene(2);
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  auto &c = sim.colloids();
  c.v[0] = {0.04, -0.03};
  c.v[1] = {-0.02, 0.05};
  c.omega[2] = {0.2, -0.15}; // a spin far above thermal (sqrt(kT / I) = 0.02)
  coupling::NoSlipParams params;
  params.dt = 1e-9; // the colloids barely move: only the collision is examined
  params.density = s.fluid.density;
  params.seed = 5;
  const parallel::Slabs slabs(MPI_COMM_SELF, 24);
  coupling::NoSlipCoupling coupling(params, sim.box(), slabs);
  mpcd::Fluid fluid = sim.fluid();
  coupling.move_colloids(fluid, c);
  mpcd::CellGrid grid(sim.box());
  double worst = 0.0, spin_change = 0.0;
  mpcd::CollisionScratch scratch;
  for (std::uint64_t step = 0; step < 20; ++step) {
    grid.set_shift(mpcd::grid_shift(5, step, 2));
    mpcd::bin_particles(fluid, grid);
    const double l0 = angular_momentum(fluid, c, grid, sim.box());
    const double w0 = c.omega[2][0];
    coupling.add_ghost_particles(grid, c, step);
    ASSERT_GT(coupling.ghost_particles(), 100u);
    mpcd::collide_at_a(fluid, grid, scratch, 1.0, 5, step);
    coupling.take_back_ghost_particles(grid, scratch, fluid, c);
    const double l1 = angular_momentum(fluid, c, grid, sim.box());
    worst = std::max(worst, std::abs(l1 - l0));
    spin_change = std::max(spin_change, std::abs(c.omega[2][0] - w0));
  }
  // Round-off: each of ~5000 terms r x v of size ~ 24 x 3 carries 2^-52 relative error, and
  // the cell sums are fixed point (2^-40 per term): below 1e-7 in all.
  std::printf("largest |L1 - L0| per collision: %.3g; largest spin change %.3g\n", worst,
              spin_change);
  EXPECT_LT(worst, 1e-7);
  EXPECT_GT(spin_change, 1e-3); // the ghosts did exchange angular momentum
}

// The implicit exchange's share of the cut cells' fluid (G dX/2) is added by MPC-AT+a's own
// particle pass when the coupling runs between its two passes (the engine's order), and by a
// pass over the fluid after a whole collision: both give the same bits, in 2D and in 3D.
namespace {

struct CouplingRun {
  colloids::Colloids c;
  mpcd::Fluid fluid;
  mpcd::CellGrid grid;
  mpcd::CollisionScratch scratch;
  coupling::NoSlipCoupling coupling;
  CouplingRun(const mpcd::MpcdSimulation &sim, const coupling::NoSlipParams &params,
              const parallel::Slabs &slabs, int dim)
      : c(sim.colloids()), fluid(sim.fluid()), grid(sim.box()), coupling(params, sim.box(), slabs) {
    c.v[0] = {0.04, -0.03};
    c.v[1] = {-0.02, 0.05};
    c.omega[2] = {0.2, -0.15}; // spins far above thermal: a large share for the fluid
    if (dim == 3)
      c.omega[0] = {-0.1, 0.12};
    coupling.move_colloids(fluid, c);
  }
};

} // namespace

class NoSlipShiftFolded : public ::testing::TestWithParam<int> {};

TEST_P(NoSlipShiftFolded, IntoTheCollisionIsThePassOverTheFluid) {
  const int dim = GetParam();
  const scene::Scene s = two_colloids_scene(dim);
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  coupling::NoSlipParams params;
  params.dt = 1e-9; // the colloids barely move: only the collision is examined
  params.density = s.fluid.density;
  params.seed = 5;
  const parallel::Slabs slabs(MPI_COMM_SELF, 24);
  CouplingRun pass(sim, params, slabs, dim), folded(sim, params, slabs, dim);
  std::size_t moved = 0;
  for (std::uint64_t step = 0; step < 5; ++step) {
    for (CouplingRun *r : {&pass, &folded}) {
      r->grid.set_shift(mpcd::grid_shift(5, step, dim));
      mpcd::bin_particles(r->fluid, r->grid);
      r->coupling.add_ghost_particles(r->grid, r->c, step);
    }
    ASSERT_GT(pass.coupling.ghost_particles(), 100u);
    mpcd::collide_at_a(pass.fluid, pass.grid, pass.scratch, 1.0, 5, step);
    const auto collided = pass.fluid.v; // (to see that the fluid's share was not nothing)
    pass.coupling.take_back_ghost_particles(pass.grid, pass.scratch, pass.fluid, pass.c);
    mpcd::collide_at_a_cells(folded.fluid, folded.grid, folded.scratch, 1.0, 5, step, true);
    folded.coupling.take_back_ghost_particles(folded.grid, folded.scratch, folded.fluid, folded.c);
    EXPECT_TRUE(folded.scratch.cells_shifted);
    mpcd::collide_at_a_particles(folded.fluid, folded.grid, folded.scratch);
    for (std::size_t i = 0; i < pass.fluid.size(); ++i)
      for (int k = 0; k < dim; ++k) {
        ASSERT_EQ(pass.fluid.v[k][i], folded.fluid.v[k][i])
            << "step " << step << ", particle " << i << ", component " << k;
        moved += pass.fluid.v[k][i] != collided[k][i];
      }
    for (std::size_t a = 0; a < pass.c.size(); ++a)
      for (int k = 0; k < 3; ++k) {
        if (k < dim)
          ASSERT_EQ(pass.c.v[k][a], folded.c.v[k][a]);
        ASSERT_EQ(pass.c.omega[k][a], folded.c.omega[k][a]);
      }
  }
  std::printf("%zu velocity components moved by the fluid's share of the exchange\n", moved);
  EXPECT_GT(moved, 100u);
}

INSTANTIATE_TEST_SUITE_P(Dims, NoSlipShiftFolded, ::testing::Values(2, 3));
