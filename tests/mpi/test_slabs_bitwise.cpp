// The sharpest test of the slab decomposition: the state after N steps on 2, 3 or 4 ranks is
// bitwise identical to the state on 1 rank (all particles compared by id, the colloids too:
// each owned by the rank of its slab, with ghost copies on the others). The box is 25 (2D) or
// 13 (3D) cells long, so the slabs are uneven on 2, 3 and 4 ranks; on 3 or more ranks each
// slab has two distinct neighbours.
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/state_by_id.hpp"
#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdlib>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

using namespace narrows;

namespace {

using narrows::testing::world_rank;
using narrows::testing::world_size;

// The slab that owns x (cells of size 1).
int owner(const parallel::Slabs &slabs, double x) {
  int r = 0;
  while (r + 1 < slabs.ranks() && slabs.first_column_of(r + 1) <= static_cast<int>(x))
    ++r;
  return r;
}

// How many colloids this rank holds whose centre lies outside its slab (each must be owned by
// the rank of its slab between steps).
std::size_t held_elsewhere(const colloids::Colloids &c, const parallel::Slabs &slabs) {
  std::size_t n = 0;
  for (std::size_t a = 0; a < c.size(); ++a)
    n += owner(slabs, c.x[0][a]) != slabs.rank();
  return n;
}

using narrows::testing::state_by_id;

struct Case {
  const char *name;
  int dim;
  scene::Collision rule;
  bool sine;               // sine force, else constant force
  bool walls = false;      // no-slip walls at y = 0 and y = L_y with virtual particles
  bool mirror = false;     // ... whose mean velocity continues the flow (walls.virtual_flow)
  bool colloids = false;   // MD-coupled colloids with gravity (walls: also the wall potential)
  bool thermostat = false; // 2D: per-layer rescaling thermostat, 3D: Monte Carlo
  double radius_sd = 0.0;  // colloid radii from a Gaussian of this standard deviation
  bool no_slip = false;    // colloids: no-slip coupling with hard contacts instead of MD
};

class Bitwise : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(Bitwise, RanksEqualOneRank) {
  const Case c = GetParam();
  scene::Scene s;
  s.run.dimensions = c.dim;
  s.run.seed = 31;
  s.domain.size = c.dim == 2 ? std::array<double, 3>{25, 10, 0} : std::array<double, 3>{13, 6, 6};
  s.fluid.collision = c.rule;
  s.fluid.density = 6.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 120.0;
  s.fluid.sort_every = 7;
  s.body_force = c.sine ? scene::BodyForce{scene::ForceKind::sine, {0, 0, 0}, 0.05}
                        : scene::BodyForce{scene::ForceKind::constant, {0.01, -0.003, 0.002}, 0};
  if (c.walls)
    s.walls =
        scene::Walls{false, true, c.mirror ? scene::VirtualFlow::mirror : scene::VirtualFlow::rest};
  if (c.thermostat) // 2D: per-layer rescaling; 3D: Monte Carlo cells
    s.thermostat = scene::Thermostat{
        c.dim == 2 ? scene::ThermostatKind::layers : scene::ThermostatKind::monte_carlo, 0.2};
  if (c.colloids) {
    scene::Colloids col;
    col.radius = c.dim == 2 ? 2.0 : 1.0;
    col.count = c.dim == 2 ? 4 : 3;
    col.placement = scene::ColloidPlacement::random;
    // Gravity is a field (force M g; M = 126 in 2D, 42 in 3D): forces of ~1 move the colloids
    // across the slab edges within the test.
    col.gravity = {0.008, 0.001, 0.0005};
    col.md_substeps = 50; // tau_MD = 0.01 (at 0.1 a fast fluid particle runs deep into a colloid)
    col.radius_sd = c.radius_sd;
    if (c.no_slip) { // bounce-back, ghost particles, rough hard-sphere contacts
      col.coupling = scene::ColloidCoupling::no_slip;
      col.contacts = scene::ColloidContacts::hard;
      col.count = c.dim == 2 ? 6 : 8; // more of them: contacts across the slab edges (3D: 4 met
                                      // in one noise realisation and not in another)
      s.fluid.dt = 0.1; // the explicit coupling's stability bound (docs/scenes.md: f <= 0.5)
      // With walls they settle onto the lower wall and the flow pushes them along it; in the
      // Kolmogorov flow they go both ways with the fluid.
      col.gravity =
          c.walls ? std::array<double, 3>{0.0, -0.02, 0.0} : std::array<double, 3>{0.0, 0.0, 0.0};
    }
    s.colloids = col;
  }
  // 2000 steps in CI on 2 ranks (~4 s), 500 on 3 and 4 (oversubscribed on 2 cores); longer by
  // hand: NARROWS_BITWISE_STEPS=20000 mpirun -n 3 mpi_tests
  const char *env = std::getenv("NARROWS_BITWISE_STEPS");
  // (colloid cases: 1000 steps of 50 MD sub-steps, 2-6 s each; 250 on 3 and 4 ranks)
  const int quarter = world_size() > 2 ? 4 : 1;
  // (no-slip cases: 1000 steps on any number of ranks, 1-3 s: enough contacts to compare)
  const int steps = env ? std::atoi(env) : c.no_slip ? 1000 : (c.colloids ? 1000 : 2000) / quarter;
  mpcd::MpcdSimulation par(s, MPI_COMM_WORLD);
  // Colloid cases must move colloids from slab to slab, else the comparison is empty for them;
  // the moves are counted both ways (to the right and to the left neighbour's slab).
  std::vector<int> slab_of;
  const auto start = par.gather_colloids(); // held: a range over a temporary's member dangles
  for (double x : start.x[0])
    slab_of.push_back(owner(par.slabs(), x));
  int moves_right = 0, moves_left = 0;
  std::size_t misplaced = 0;
  for (int i = 0; i < steps; ++i) {
    par.advance();
    if (!c.colloids)
      continue;
    misplaced += held_elsewhere(par.colloids(), par.slabs());
    const auto all = par.gather_colloids();
    ASSERT_EQ(all.size(), slab_of.size()) << "colloids lost or doubled at step " << i;
    for (std::size_t a = 0; a < all.size(); ++a) {
      const int now = owner(par.slabs(), all.x[0][a]), ranks = world_size();
      if (now == (slab_of[a] + 1) % ranks)
        ++moves_right;
      else if (now != slab_of[a])
        ++moves_left;
      slab_of[a] = now;
    }
  }
  if (c.colloids && world_size() > 1) {
    EXPECT_GT(moves_right + moves_left, 0)
        << "no colloid crossed a slab edge in " << steps << " steps";
    std::printf("colloid slab changes: %d to the right, %d to the left\n", moves_right, moves_left);
    if (const auto *ns = par.no_slip()) { // contacts this rank resolved, ghosts included
      std::printf("rank %d: %llu colloid-colloid and %llu colloid-wall collisions\n", world_rank(),
                  static_cast<unsigned long long>(ns->contacts().pair_collisions),
                  static_cast<unsigned long long>(ns->contacts().wall_collisions));
      EXPECT_GT(ns->contacts().pair_collisions, 0u) << "no contact to compare";
    }
  }
  EXPECT_EQ(misplaced, 0u) << "colloids held by a rank whose slab does not hold their centre";
  const auto total = mpcd::particle_count(s);
  const auto two = state_by_id(par.fluid(), total, MPI_COMM_WORLD);
  const auto gathered = par.gather_colloids();
  if (world_rank() != 0)
    return;
  mpcd::MpcdSimulation ser(s, MPI_COMM_SELF);
  for (int i = 0; i < steps; ++i)
    ser.advance();
  const auto one = state_by_id(ser.fluid(), total, MPI_COMM_SELF);
  // Colloids: all of them, gathered from their owners by id, against the serial run's.
  const auto &ca = gathered, &cb = ser.colloids();
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t a = 0; a < ca.size(); ++a)
    ASSERT_EQ(ca.id[a], cb.id[a]);
  std::size_t colloid_differ = 0;
  for (int k = 0; k < c.dim; ++k)
    for (std::size_t a = 0; a < ca.size(); ++a)
      colloid_differ += std::memcmp(&ca.x[k][a], &cb.x[k][a], sizeof(double)) != 0 ||
                        std::memcmp(&ca.v[k][a], &cb.v[k][a], sizeof(double)) != 0;
  for (int k = 0; k < 3; ++k) // angular velocities (no-slip colloids spin)
    for (std::size_t a = 0; a < ca.size(); ++a)
      colloid_differ += std::memcmp(&ca.omega[k][a], &cb.omega[k][a], sizeof(double)) != 0;
  for (int k = 0; k < 4; ++k) // and turn
    for (std::size_t a = 0; a < ca.size(); ++a)
      colloid_differ += std::memcmp(&ca.q[k][a], &cb.q[k][a], sizeof(double)) != 0;
  for (std::size_t a = 0; a < ca.size(); ++a) // radii and masses (drawn from the seed)
    colloid_differ += std::memcmp(&ca.radius[a], &cb.radius[a], sizeof(double)) != 0 ||
                      std::memcmp(&ca.mass[a], &cb.mass[a], sizeof(double)) != 0;
  EXPECT_EQ(colloid_differ, 0u);
  std::size_t differ = 0;
  for (std::size_t j = 0; j < one.size(); ++j)
    differ += std::memcmp(&one[j], &two[j], sizeof(double)) != 0;
  EXPECT_EQ(differ, 0u) << differ << " of " << one.size() << " numbers differ after " << steps
                        << " steps on " << world_size() << " ranks";
}

INSTANTIATE_TEST_SUITE_P(
    Rules, Bitwise,
    ::testing::Values(
        Case{"srd2d_constant", 2, scene::Collision::srd, false},
        Case{"srd3d_sine", 3, scene::Collision::srd, true},
        Case{"srd2d_sine", 2, scene::Collision::srd, true},
        Case{"at_a2d_constant", 2, scene::Collision::at_a, false},
        Case{"at_a3d_sine", 3, scene::Collision::at_a, true},
        Case{"at3d_constant", 3, scene::Collision::at, false},
        Case{"maxwell2d_constant", 2, scene::Collision::random_maxwell, false},
        Case{"srd2d_walls", 2, scene::Collision::srd, false, true},
        Case{"srd3d_walls_mirror", 3, scene::Collision::srd, false, true, true},
        Case{"at_a2d_walls", 2, scene::Collision::at_a, false, true},
        Case{"at3d_walls", 3, scene::Collision::at, false, true},
        Case{"srd2d_colloids", 2, scene::Collision::srd, false, false, false, true},
        Case{"srd2d_walls_colloids", 2, scene::Collision::srd, false, true, false, true},
        Case{"srd3d_walls_colloids", 3, scene::Collision::srd, false, true, false, true},
        Case{"srd2d_walls_colloids_thermostat", 2, scene::Collision::srd, false, true, false, true,
             true},
        Case{"srd3d_sine_thermostat", 3, scene::Collision::srd, true, false, false, false, true},
        // unequal radii: sd 0.2 r (0.4 of 2), or with walls in 3D 0.1 (the largest wall cut-off,
        // 1.0631 * 2 (1 + 0.3), must fit in half the width of 6)
        Case{"srd2d_colloids_radius_sd", 2, scene::Collision::srd, false, false, false, true, false,
             0.4},
        Case{"srd3d_walls_colloids_radius_sd", 3, scene::Collision::srd, false, true, false, true,
             false, 0.1},
        // no-slip colloids with hard contacts (Kanehl (thesis) §4.2.1-4.2.2)
        Case{"at_a2d_walls_noslip_hard", 2, scene::Collision::at_a, false, true, false, true, false,
             0.3, true},
        Case{"srd3d_sine_noslip_hard", 3, scene::Collision::srd, true, false, false, true, false,
             0.0, true},
        Case{"at2d_sine_noslip_hard", 2, scene::Collision::at, true, false, false, true, false, 0.0,
             true}),
    [](const auto &info) { return std::string(info.param.name); });
