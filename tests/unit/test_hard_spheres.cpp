// Event-driven rough hard spheres (Kanehl (thesis) §4.2.2): one collision reverses the relative
// velocity of the touching surfaces and conserves momentum, angular momentum and energy; a
// rough wall reverses the contact velocity; many disks and spheres over many steps keep their
// energy and momentum to round-off and never overlap.
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/pair_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace narrows;
using namespace narrows::colloids;

namespace {

Colloids make(int dim, std::size_t n) {
  Colloids c;
  c.dim = dim;
  c.resize(n);
  for (std::size_t a = 0; a < n; ++a)
    c.id[a] = a;
  return c;
}

// The velocity of the surface point of colloid a at offset s from its centre: v + omega x s.
std::array<double, 3> surface_velocity(const Colloids &c, std::size_t a, const double s[3]) {
  std::array<double, 3> u{0.0, 0.0, 0.0};
  for (int k = 0; k < c.dim; ++k)
    u[k] = c.v[k][a];
  u[0] += c.omega[1][a] * s[2] - c.omega[2][a] * s[1];
  u[1] += c.omega[2][a] * s[0] - c.omega[0][a] * s[2];
  u[2] += c.omega[0][a] * s[1] - c.omega[1][a] * s[0];
  return u;
}

// Momentum and angular momentum about the origin (orbital plus spin), 3 components each.
std::array<double, 6> momenta(const Colloids &c) {
  std::array<double, 6> p{};
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double m = c.mass[a], i = moment_of_inertia(c, a);
    double x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int k = 0; k < c.dim; ++k) {
      x[k] = c.x[k][a];
      v[k] = c.v[k][a];
      p[k] += m * v[k];
    }
    p[3] += m * (x[1] * v[2] - x[2] * v[1]) + i * c.omega[0][a];
    p[4] += m * (x[2] * v[0] - x[0] * v[2]) + i * c.omega[1][a];
    p[5] += m * (x[0] * v[1] - x[1] * v[0]) + i * c.omega[2][a];
  }
  return p;
}

// The box of the many-collision tests: 30 x 30 (2D) or 14^3 (3D), periodic or with walls along y.
mpcd::Box lattice_box(int dim, bool walls) {
  const int side = dim == 2 ? 30 : 14;
  mpcd::Box box = mpcd::make_periodic_box(dim, {side, side, dim == 3 ? side : 1});
  box.walls_y = walls;
  return box;
}

// n colloids on a lattice in the box (no overlap), radii 1 and 1.4 alternating, random
// velocities and spins.
Colloids lattice_start(int dim, std::size_t n, const mpcd::Box &box, std::uint64_t seed) {
  Colloids c = make(dim, n);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const int per_row = dim == 2 ? 8 : 5;
  const double spacing = box.length[0] / per_row;
  for (std::size_t a = 0; a < n; ++a) {
    c.radius[a] = a % 2 ? 1.4 : 1.0;
    c.mass[a] = 3.0 * c.radius[a] * c.radius[a];
    std::size_t q = a;
    for (int k = 0; k < dim; ++k) {
      c.x[k][a] = (static_cast<double>(q % per_row) + 0.5) * spacing;
      q /= per_row;
      c.v[k][a] = g(rng);
    }
    for (int k = dim == 2 ? 2 : 0; k < 3; ++k)
      c.omega[k][a] = g(rng);
  }
  return c;
}

} // namespace

TEST(HardSpheres, HeadOnEqualDisksExchangeVelocitiesAtTheContactTime) {
  Colloids c = make(2, 2);
  const mpcd::Box box = mpcd::make_periodic_box(2, {40, 40, 1});
  c.x[0] = {10.0, 16.0};
  c.x[1] = {20.0, 20.0};
  c.v[0] = {1.0, -1.0};
  c.radius = {1.0, 2.0};
  c.mass = {3.0, 3.0};
  // The gap of 3 closes at relative speed 2 after t = 1.5; then the velocities swap.
  const HardSphereStats s = advance_hard_spheres(c, box, 2.0);
  EXPECT_EQ(s.pair_collisions, 1u);
  EXPECT_DOUBLE_EQ(c.v[0][0], -1.0);
  EXPECT_DOUBLE_EQ(c.v[0][1], 1.0);
  EXPECT_NEAR(c.x[0][0], 10.0 + 1.5 - 0.5, 1e-12);
  EXPECT_NEAR(c.x[0][1], 16.0 - 1.5 + 0.5, 1e-12);
  EXPECT_EQ(c.omega[2][0], 0.0); // head on: no torque
}

TEST(HardSpheres, ObliqueSpinningCollisionReversesTheContactVelocityAndConservesAll) {
  for (int dim : {2, 3}) {
    Colloids c = make(dim, 2);
    c.radius = {1.0, 1.7};
    c.mass = {2.0, 5.0};
    // Touching: d = x_a - x_b along a unit vector n, |d| = 2.7.
    const double n[3] = {0.6, 0.8 * (dim == 3 ? 0.6 : 1.0), dim == 3 ? 0.8 * 0.8 : 0.0};
    for (int k = 0; k < dim; ++k) {
      c.x[k][1] = 5.0 + k;
      c.x[k][0] = c.x[k][1] + 2.7 * n[k];
    }
    const double va[3] = {-0.4, -0.9, 0.3}, vb[3] = {0.2, 0.1, -0.5};
    for (int k = 0; k < dim; ++k) {
      c.v[k][0] = va[k];
      c.v[k][1] = vb[k];
    }
    c.omega[2] = {0.7, -0.3};
    if (dim == 3) {
      c.omega[0] = {0.2, 0.5};
      c.omega[1] = {-0.6, 0.1};
    }
    const double sa[3] = {-1.0 * n[0], -1.0 * n[1], -1.0 * n[2]}; // contact point from a
    const double sb[3] = {1.7 * n[0], 1.7 * n[1], 1.7 * n[2]};    // and from b
    const auto ua = surface_velocity(c, 0, sa), ub = surface_velocity(c, 1, sb);
    const auto before = momenta(c);
    const double e0 = kinetic_energy(c);
    double d[3] = {0, 0, 0};
    for (int k = 0; k < dim; ++k)
      d[k] = c.x[k][0] - c.x[k][1];
    collide_rough(c, 0, 1, d);
    const auto ua2 = surface_velocity(c, 0, sa), ub2 = surface_velocity(c, 1, sb);
    for (int k = 0; k < 3; ++k) // U' = -U, normal and tangential parts alike (fig 4.5)
      EXPECT_NEAR(ua2[k] - ub2[k], -(ua[k] - ub[k]), 1e-14) << "dim " << dim << " k " << k;
    const auto after = momenta(c);
    for (int q = 0; q < 6; ++q)
      EXPECT_NEAR(after[q], before[q], 1e-13) << "dim " << dim << " component " << q;
    EXPECT_NEAR(kinetic_energy(c), e0, 1e-14 * e0) << "dim " << dim;
  }
}

TEST(HardSpheres, RoughWallReversesTheContactVelocityAndKeepsTheEnergy) {
  for (int dim : {2, 3})
    for (int side : {+1, -1}) {
      Colloids c = make(dim, 1);
      c.radius = {1.5};
      c.mass = {4.0};
      c.v[0][0] = 0.8;
      c.v[1][0] = -0.5 * side;
      c.omega[2][0] = 0.4;
      if (dim == 3) {
        c.v[2][0] = -0.3;
        c.omega[0][0] = 0.9;
      }
      const double s[3] = {0.0, -1.5 * side, 0.0}; // the contact point from the centre
      const auto u = surface_velocity(c, 0, s);
      const double e0 = kinetic_energy(c);
      collide_rough_wall(c, 0, side);
      const auto u2 = surface_velocity(c, 0, s);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(u2[k], -u[k], 1e-14) << "dim " << dim << " side " << side << " k " << k;
      EXPECT_NEAR(kinetic_energy(c), e0, 1e-14 * e0);
    }
}

// A gas of disks or spheres at packing fraction ~0.2-0.3: thousands of collisions, energy and
// (periodic box) momentum to round-off, never an overlap at the end of a step.
TEST(HardSpheres, ManyCollisionsKeepEnergyMomentumAndNoOverlap) {
  for (int dim : {2, 3})
    for (bool walls : {false, true}) {
      mpcd::Box box = lattice_box(dim, walls);
      const std::size_t n = dim == 2 ? 60 : 80;
      Colloids c = lattice_start(dim, n, box, 7 + dim + 10 * walls);
      const double e0 = kinetic_energy(c);
      const auto p0 = momenta(c);
      HardSphereStats total;
      for (int step = 0; step < 500; ++step) {
        const HardSphereStats s = advance_hard_spheres(c, box, 0.1);
        total.pair_collisions += s.pair_collisions;
        total.wall_collisions += s.wall_collisions;
      }
      SCOPED_TRACE("dim " + std::to_string(dim) + (walls ? " walls" : " periodic"));
      EXPECT_GT(total.pair_collisions, 1000u);
      if (walls)
        EXPECT_GT(total.wall_collisions, 50u);
      EXPECT_NEAR(kinetic_energy(c), e0, 1e-11 * e0);
      const auto p = momenta(c);
      for (int k = 0; k < dim; ++k)
        if (!walls) // a rough wall takes momentum along and across it
          EXPECT_NEAR(p[k], p0[k], 1e-10 * std::sqrt(e0)) << "momentum " << k;
      double worst = 1.0; // smallest distance / contact distance
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b) {
          double r2 = 0.0;
          for (int k = 0; k < dim; ++k) {
            double d = c.x[k][a] - c.x[k][b];
            if (!(walls && k == 1))
              d = minimum_image(d, box.length[k]);
            r2 += d * d;
          }
          worst = std::min(worst, std::sqrt(r2) / (c.radius[a] + c.radius[b]));
        }
      EXPECT_GT(worst, 1.0 - 1e-9) << "overlap";
      if (walls)
        for (std::size_t a = 0; a < n; ++a) {
          EXPECT_GE(c.x[1][a], c.radius[a] * (1.0 - 1e-12));
          EXPECT_LE(c.x[1][a], box.length[1] - c.radius[a] * (1.0 - 1e-12));
        }
      std::printf(
          "dim %d %s: %llu pair and %llu wall collisions, energy drift %.2e\n", dim,
          walls ? "walls" : "periodic", static_cast<unsigned long long>(total.pair_collisions),
          static_cast<unsigned long long>(total.wall_collisions), kinetic_energy(c) / e0 - 1.0);
    }
}

// The events of a step are predicted only for pairs in neighbouring cells of the start
// positions (cells at least as wide as a pair can close in a step); that finds every event of
// the step, so a long run ends bitwise where predicting every pair does. 2D: 7 x 7 cells, 3D:
// 3 x 3 x 3 (periodic, and with walls along y).
TEST(HardSpheres, NeighbourCellsPredictTheEventsOfEveryPair) {
  for (int dim : {2, 3})
    for (bool walls : {false, true}) {
      mpcd::Box box = lattice_box(dim, walls);
      const std::size_t n = dim == 2 ? 60 : 80;
      Colloids c = lattice_start(dim, n, box, 17 + dim + 10 * walls);
      Colloids every = c;
      std::uint64_t collisions = 0;
      for (int step = 0; step < 500; ++step) {
        collisions += advance_hard_spheres(c, box, 0.1).pair_collisions;
        advance_hard_spheres(every, box, 0.1, nullptr, true);
      }
      SCOPED_TRACE("dim " + std::to_string(dim) + (walls ? " walls" : " periodic"));
      EXPECT_GT(collisions, 1000u);
      for (std::size_t a = 0; a < n; ++a)
        for (int k = 0; k < 3; ++k) {
          if (k < dim) {
            EXPECT_EQ(c.x[k][a], every.x[k][a]) << "colloid " << a << " x " << k;
            EXPECT_EQ(c.v[k][a], every.v[k][a]) << "colloid " << a << " v " << k;
          }
          EXPECT_EQ(c.omega[k][a], every.omega[k][a]) << "colloid " << a << " omega " << k;
        }
    }
}

// A few colloids in a huge box: the cells stay few (about 8 a colloid, each still at least as
// wide as a pair can close in a step), not one per such width of the box (1e11 here), and the
// events are still those of every pair.
TEST(HardSpheres, FewColloidsInAHugeBoxNeedFewCells) {
  const mpcd::Box box = mpcd::make_periodic_box(3, {10000, 10000, 10000});
  Colloids c = make(3, 4);
  for (std::size_t a = 0; a < 4; ++a) {
    c.radius[a] = 1.0;
    c.mass[a] = 1.0;
    c.x[0][a] = 5000.0 + 3.0 * static_cast<double>(a); // in a row, 1 apart
    c.x[1][a] = c.x[2][a] = 5000.0;
    c.v[0][a] = a % 2 ? -1.0 : 1.0; // approaching in pairs
  }
  Colloids every = c;
  std::uint64_t collisions = 0;
  for (int step = 0; step < 10; ++step) {
    collisions += advance_hard_spheres(c, box, 0.2).pair_collisions;
    advance_hard_spheres(every, box, 0.2, nullptr, true);
  }
  EXPECT_GT(collisions, 0u);
  for (std::size_t a = 0; a < 4; ++a)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(c.x[k][a], every.x[k][a]);
      EXPECT_EQ(c.v[k][a], every.v[k][a]);
    }
}
