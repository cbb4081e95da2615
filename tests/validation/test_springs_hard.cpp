// Spring contacts in the fluid. Issue 21 acceptance 5 (the spring part): no-slip colloids with
// linear springs and Coulomb friction in a hard case, 10^5 steps (10^6 sub-steps): three disks in a
// pyramid on the lower wall, pressed down by gravity (M g = 50: overlaps of 1 % of the radius),
// with friction that never slides (mu = inf between them and with the wall), so that each lower
// disk is wedged between the other two and the wall and the pyramid is jammed; the fluid pushes
// along the channel. Every 100 steps: the run's invariants (count, ids, no NaN or runaway speed),
// no fluid particle inside a colloid, the colloid count, the contacts. At the end the deepest
// overlap is reported: the kicks of fluid trapped in the gaps at the contacts make it deeper than
// the static 1 % (measured 5 %; the thesis' fig 6.2a has a tail beyond 4 %), and below 10 % is
// asked. The pyramid does not stay jammed at kT = 1: those kicks open a contact now and then, which
// drops its tangential spring (the history lasts as long as the contact), and the disks creep
// apart over the run.
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/engines/mpcd/totals.hpp"
#include "narrows/scene/parse.hpp"

#include "colloid_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

using namespace narrows;

namespace {

// The deepest overlap of the colloids with each other and with the walls (all pairs).
double deepest_overlap(const mpcd::MpcdSimulation &sim) {
  const auto &col = sim.colloids();
  const double L = sim.box().length[0];
  double worst = 0.0;
  for (std::size_t a = 0; a < col.size(); ++a) {
    worst = std::max(
        {worst, col.radius[a] - col.x[1][a], col.x[1][a] + col.radius[a] - sim.box().length[1]});
    for (std::size_t b = a + 1; b < col.size(); ++b) {
      double dx = col.x[0][a] - col.x[0][b];
      dx -= L * std::round(dx / L);
      worst = std::max(worst,
                       col.radius[a] + col.radius[b] - std::hypot(dx, col.x[1][a] - col.x[1][b]));
    }
  }
  return worst;
}

} // namespace

TEST(SpringHardCase, DiskWedgedBetweenTwoOthersAndAWall) {
  scene::Colloids c;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.contacts = scene::ColloidContacts::spring;
  c.spring = {2500.0, 2500.0, std::numeric_limits<double>::infinity(),
              std::numeric_limits<double>::infinity(), 10};
  c.radius = 2.0;
  c.count = 3;
  c.placement = scene::ColloidPlacement::list;
  // Two on the wall touching, the third on top of both (a hair apart, which the placement check
  // would otherwise round to an overlap).
  const double up = 2.0 + 2.0 * std::sqrt(3.0) + 1e-8;
  c.positions = {{6.0, 2.0 + 1e-9, 0.0}, {10.0 + 1e-9, 2.0 + 1e-9, 0.0}, {8.0, up, 0.0}};
  c.gravity = {0.0, -1.0, 0.0};
  scene::Scene s = narrows::testing::srd_colloid_scene(16.0, 10.0, true, 4, c);
  s.fluid.collision = scene::Collision::at_a;
  s.fluid.density = 4.0;
  s.fluid.dt = 0.05;
  s.walls->virtual_particles = true;
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.005, 0.0, 0.0}, 0.0};
  const int steps = 100000;

  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const mpcd::InvariantCheck invariants(sim);
  double deepest = 0.0, inside = 1e9;
  std::size_t most_contacts = 0, fewest_contacts = 100;
  for (int step = 1; step <= steps; ++step) {
    sim.advance();
    if (step % 100 != 0)
      continue;
    EXPECT_NO_THROW(invariants.check(sim)) << "step " << step;
    const auto &col = sim.colloids();
    ASSERT_EQ(col.size(), 3u) << "step " << step;
    const double L = sim.box().length[0];
    deepest = std::max(deepest, deepest_overlap(sim));
    const auto &f = sim.fluid();
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t a = 0; a < col.size(); ++a) {
        double dx = f.x[0][i] - col.x[0][a];
        dx -= L * std::round(dx / L);
        inside = std::min(inside, std::hypot(dx, f.x[1][i] - col.x[1][a]) / col.radius[a]);
      }
    most_contacts = std::max(most_contacts, sim.no_slip()->contact_history().size());
    fewest_contacts = std::min(fewest_contacts, sim.no_slip()->contact_history().size());
    if (::testing::Test::HasFailure())
      break;
  }
  const auto *springs = sim.no_slip()->springs();
  std::printf("[ measured ] wedged disk: %d steps; deepest overlap %.3g radii; closest fluid "
              "%.12f radii; %zu to %zu contacts at once; %llu contact updates, %llu sliding; "
              "colloid x: %.3g %.3g %.3g\n",
              steps, deepest / 2.0, inside, fewest_contacts, most_contacts,
              static_cast<unsigned long long>(springs->contact_updates()),
              static_cast<unsigned long long>(springs->sliding_updates()), sim.colloids().x[0][0],
              sim.colloids().x[0][1], sim.colloids().x[0][2]);
  EXPECT_GE(inside, 1.0);
  EXPECT_LT(deepest, 0.1 * 2.0);
  EXPECT_GE(most_contacts, 4u);
}

// Issue 21 acceptance 5, the first and third hard cases, 10^5 steps (10^6 sub-steps): the
// thesis' Table 6.1 mixture (a = 2.1 and 2.94, 1 : 1) packed to phi = 0.82 in a walled channel
// (2w = 50, l = 100: 200 disks; at l = 60 the packing jams below 0.82), friction that never slides
// (mu = inf between the disks and with the walls), under the thesis' strongest drive (sigma = 1.25:
// 0.05 per fluid particle, and the same pressure gradient on the colloids, M g = sigma V),
// MPC-AT+a, n = 25, dt = 0.02, as run/pulses_table6_1.toml. At phi = 0.82 most of the fluid sits
// in gaps between surfaces thinner than one cell; the run counts those particles at the end (the
// third hard case: fluid trapped in a gap thinner than a cell). Every 100 steps: the invariants
// (count, ids, no NaN or runaway speed); every step the bounce-back refuses a particle left inside
// a colloid (invariant_error), so the run finishing is the no-fluid-inside check. No colloid lost,
// no disk's centre inside another (the deepest overlap below 0.6 of the small radius: under this
// drive the springs of k_n = 2500 give way, 0.46 of it measured, 1.04 with k_n halved), no
// sliding contact (mu = inf) and no flow of the locked packing (mean colloid v_x < 0.05, 0.008
// measured, 0.73 with the tangential spring dropped). ~3 min on one core (label validation-hard).
TEST(SpringHardCase, DensePackingWithoutSlidingUnderTheStrongestDrive) {
  // (Through the parser: it turns the number ratio and the fraction into counts.)
  const scene::Scene s = scene::parse_scene(R"(
[run]
dimensions = 2
seed = 821
steps = 100000
[domain]
size = [100.0, 50.0]
[fluid]
collision = "at+a"
density = 25
dt = 0.02
[body_force]
value = [0.05, 0.0]
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
placement = "packing"
packing_fraction = 0.82
gravity = [0.05, 0.0]
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = "inf"
mu_cw = "inf"
substeps = 10
[[colloids.kind]]
radius = 2.1
count = 1
[[colloids.kind]]
radius = 2.94
count = 1
)",
                                            "dense_packing.toml");
  const int steps = 100000;

  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const mpcd::InvariantCheck invariants(sim);
  const std::size_t n = sim.colloids().size();
  ASSERT_EQ(n, 200u);
  const double r_small = 2.1;
  double deepest = 0.0, fastest = 0.0, spin = 0.0, drift = 0.0; // max |omega|, mean <v_x>
  std::vector<double> per_tenth(10, 0.0); // the deepest overlap in each tenth of the run
  for (int step = 1; step <= steps; ++step) {
    ASSERT_NO_THROW(sim.advance()) << "step " << step;
    if (step % 100 != 0)
      continue;
    ASSERT_NO_THROW(invariants.check(sim)) << "step " << step;
    ASSERT_EQ(sim.colloids().size(), n) << "step " << step;
    const double now = deepest_overlap(sim);
    deepest = std::max(deepest, now);
    double &tenth = per_tenth[static_cast<std::size_t>((step - 1) / (steps / 10))];
    tenth = std::max(tenth, now);
    for (std::size_t a = 0; a < n; ++a) {
      fastest = std::max(fastest, std::hypot(sim.colloids().v[0][a], sim.colloids().v[1][a]));
      spin = std::max(spin, std::abs(sim.colloids().omega[2][a]));
      drift += sim.colloids().v[0][a] / static_cast<double>(n) / (steps / 100);
    }
  }
  // Fluid in gaps thinner than one cell: a particle whose two nearest surfaces (colloids or
  // walls) are less than one cell apart through it.
  const auto &col = sim.colloids();
  const auto &f = sim.fluid();
  const double L = sim.box().length[0], H = sim.box().length[1];
  std::size_t trapped = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    double d1 = std::min(f.x[1][i], H - f.x[1][i]), d2 = 1e9; // nearest and second nearest
    for (std::size_t a = 0; a < col.size(); ++a) {
      double dx = f.x[0][i] - col.x[0][a];
      dx -= L * std::round(dx / L);
      const double d = std::hypot(dx, f.x[1][i] - col.x[1][a]) - col.radius[a];
      if (d < d1) {
        d2 = d1;
        d1 = d;
      } else {
        d2 = std::min(d2, d);
      }
    }
    trapped += d1 + d2 < 1.0;
  }
  std::printf("[ measured ] phi = 0.82, mu = inf, g = 0.05: %d steps, %zu disks, deepest overlap "
              "%.3g of the small radius, fastest disk %.3g, %zu of %zu fluid particles in gaps "
              "thinner than one cell at the end, %llu contact updates (%llu sliding)\n",
              steps, n, deepest / r_small, fastest, trapped, f.size(),
              static_cast<unsigned long long>(sim.no_slip()->springs()->contact_updates()),
              static_cast<unsigned long long>(sim.no_slip()->springs()->sliding_updates()));
  std::printf("[ measured ] fastest spin max |omega| %.4g, mean colloid v_x %.4g\n", spin, drift);
  std::printf("[ measured ] deepest overlap / small radius in each tenth of the run:");
  for (const double d : per_tenth)
    std::printf(" %.3g", d / r_small);
  std::printf("\n");
  // Without sliding: mu = inf, so no contact update may cut a tangential spring, and the packing
  // does not flow (contacts that cannot slide lock it): mean colloid v_x over the run measured
  // 0.0082; with the tangential spring dropped (contacts slide freely) 0.73, so 0.05.
  EXPECT_EQ(sim.no_slip()->springs()->sliding_updates(), 0u);
  EXPECT_LT(drift, 0.05);
  // Overlap: 0.46 of the small radius measured (0.24-0.46 per tenth); k_n halved gives 1.04.
  EXPECT_LT(deepest, 0.6 * r_small);
  EXPECT_GT(trapped, 0u);
}

// Momentum: in a periodic box (MPC-AT+a, no drive) eight disks with spring contacts and friction
// collide with each other; every pair force is added to one colloid and subtracted from the other
// in fixed point, and the bounce-back onto a rim hands the colloid what the particle loses, so
// the total momentum of fluid and colloids stays put to round-off over 3000 steps (the bound of
// tests/validation/test_no_slip_conservation.cpp: 2 N 2^-40 per step).
TEST(SpringConservation, TotalMomentumWithContacts) {
  scene::Colloids c;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.contacts = scene::ColloidContacts::spring;
  c.spring = {2500.0, 2500.0, 0.5, 0.5, 10};
  c.radius = 2.5;
  c.count = 8;
  c.placement = scene::ColloidPlacement::random;
  scene::Scene s = narrows::testing::srd_colloid_scene(24.0, 24.0, false, 12, c);
  s.fluid.collision = scene::Collision::at_a;
  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const auto p0 = mpcd::total_momentum(sim);
  const int steps = 3000;
  double max_dp = 0.0;
  for (int i = 1; i <= steps; ++i) {
    sim.advance();
    if (i % 50 == 0) {
      const auto p = mpcd::total_momentum(sim);
      for (int k = 0; k < 2; ++k)
        max_dp = std::max(max_dp, std::abs(p[k] - p0[k]));
    }
  }
  const double n = static_cast<double>(mpcd::particle_count(s));
  const double bound = 2.0 * n * 0x1p-40 * (steps + 1.0);
  const auto *springs = sim.no_slip()->springs();
  std::printf("max |P - P0| = %.3g over %d steps (round-off bound %.3g); %llu contact updates, "
              "%llu sliding\n",
              max_dp, steps, bound, static_cast<unsigned long long>(springs->contact_updates()),
              static_cast<unsigned long long>(springs->sliding_updates()));
  EXPECT_LT(max_dp, bound);
  EXPECT_GT(springs->contact_updates(), 100u); // they did collide
}
