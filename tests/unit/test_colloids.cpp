// Colloid potentials and MD forces: forces are minus gradients (finite differences), the wall
// potential's minimum is its cut-off, Newton's third law holds exactly in fixed point, and the
// placement keeps colloids apart and fluid out of them.
#include "narrows/colloids/md_coupling.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/mpcd/streaming.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <random>

using namespace narrows;
using namespace narrows::colloids;

namespace {

// Central difference of f at x with step h; error O(h^2 f''').
template <class F> double derivative(F f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

} // namespace

TEST(ColloidPotentials, PairForcesAreMinusGradients) {
  for (const double sigma : {1.0, 2.0, 4.0}) {
    const double s2 = sigma * sigma;
    for (double u = 0.9; u < 1.12; u += 0.01) {
      const double r = u * sigma;
      // 12-6 (eq 3.42) and 48-24 (eq 3.43) at the same distances (48-24 only inside its range)
      const auto e6 = [&](double q) { return repulsive_pair<6>(q * q, s2, 1.5).energy; };
      const double f6 = repulsive_pair<6>(r * r, s2, 1.5).f_over_r * r;
      EXPECT_NEAR(f6, -derivative(e6, r, 1e-6 * sigma), 1e-6 * (1.0 + std::abs(f6))) << r;
      if (r < repulsive_cutoff(24, sigma)) {
        const auto e24 = [&](double q) { return repulsive_pair<24>(q * q, s2, 1.0).energy; };
        const double f24 = repulsive_pair<24>(r * r, s2, 1.0).f_over_r * r;
        EXPECT_NEAR(f24, -derivative(e24, r, 1e-7 * sigma), 1e-5 * (1.0 + std::abs(f24))) << r;
      }
    }
  }
}

TEST(ColloidPotentials, PairPotentialsVanishWithTheirForceAtTheCutoff) {
  for (const int n : {6, 24}) {
    const double rc = repulsive_cutoff(n, 2.0);
    const auto t =
        n == 6 ? repulsive_pair<6>(rc * rc, 4.0, 1.0) : repulsive_pair<24>(rc * rc, 4.0, 1.0);
    EXPECT_NEAR(t.energy, 0.0, 1e-13);
    EXPECT_NEAR(t.f_over_r, 0.0, 1e-12);
  }
}

TEST(ColloidPotentials, WallForceIsMinusGradientAndMinimumIsTheCutoff) {
  const double sigma = 4.0, eps = 1.0, q = 1.0;
  const double hc = wall_cutoff(sigma);
  // The derived cut-off: (h/sigma)^6 = 231/160.
  EXPECT_NEAR(std::pow(hc / sigma, 6), 1.44375, 1e-14);
  EXPECT_NEAR(hc / sigma, 1.0631193, 1e-7);
  for (double h = 0.8 * sigma; h < hc; h += 0.01 * sigma) {
    const auto e = [&](double y) { return wall_term(y, sigma, eps, q).energy; };
    const double f = wall_term(h, sigma, eps, q).force;
    EXPECT_NEAR(f, -derivative(e, h, 1e-6), 1e-6 * (1.0 + std::abs(f))) << h;
    EXPECT_GT(wall_term(h, sigma, eps, q).energy, 0.0) << h; // above the minimum everywhere
  }
  // Minimum at the cut-off: energy and force vanish there (continuous potential and force),
  // and the unshifted potential has its least value there.
  EXPECT_NEAR(wall_term(hc, sigma, eps, q).energy, 0.0, 1e-13);
  EXPECT_NEAR(wall_term(hc, sigma, eps, q).force, 0.0, 1e-13);
  EXPECT_GT(wall_term(hc * 0.999, sigma, eps, q).energy, 0.0);
  EXPECT_GT(wall_term(hc * 1.001, sigma, eps, q).energy, 0.0); // the untruncated continuation rises
  EXPECT_GT(wall_term(hc * 0.999, sigma, eps, q).force, 0.0);  // pushes into the channel inside
  EXPECT_LT(wall_term(hc * 1.001, sigma, eps, q).force, 0.0);  // and would attract beyond
}

namespace {

// A small 2D channel (or periodic box) with colloids and fluid particles scattered among them.
struct Config {
  mpcd::Box box;
  mpcd::Fluid fluid;
  Colloids colloids;
  MdParams params;
};

Config make_config(bool walls, unsigned seed) {
  Config c;
  c.box = mpcd::make_periodic_box(2, {16, 10, 1});
  c.box.walls_y = walls;
  c.params.sigma_cf = 2.0;
  c.params.sigma_cc = 4.0;
  c.params.sigma_wall = 4.0;
  c.params.gravity = {0.3, -0.1, 0.0};
  c.colloids.dim = 2;
  c.colloids.resize(3);
  const double pos[3][2] = {{3.0, 4.7}, {7.1, 5.4}, {14.9, 5.0}}; // 0-1 and 2-0 (periodic) overlap
  for (int a = 0; a < 3; ++a) {
    c.colloids.x[0][a] = pos[a][0];
    c.colloids.x[1][a] = pos[a][1];
    c.colloids.mass[a] = 50.0 + 10.0 * a; // unequal, so gravity's M g is checked per colloid
    c.colloids.radius[a] = 2.0;
    c.colloids.id[a] = a;
  }
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> ux(0.0, 16.0), uy(0.0, 10.0);
  c.fluid.dim = 2;
  for (int i = 0; i < 400; ++i) {
    const std::array<double, 3> p{ux(gen), uy(gen), 0.0};
    // keep the forces moderate: nobody deeper than 0.9 sigma_cf inside a colloid
    bool ok = true;
    for (int a = 0; a < 3; ++a) {
      const double dx = mpcd::wrap_periodic(p[0] - pos[a][0] + 8.0, 16.0) - 8.0;
      ok = ok && std::hypot(dx, p[1] - pos[a][1]) > 1.8;
    }
    if (!ok)
      continue;
    c.fluid.resize(c.fluid.size() + 1);
    c.fluid.x[0].back() = p[0];
    c.fluid.x[1].back() = p[1];
    c.fluid.id.back() = i;
  }
  return c;
}

MdCoupling make_md(const Config &c) {
  return MdCoupling(c.params, c.box, [](mpcd::Fluid &, double) {});
}

} // namespace

TEST(ColloidForces, AreMinusGradientsOfThePotentialEnergy) {
  for (const bool walls : {true, false}) {
    Config c = make_config(walls, 5);
    c.params.gravity = {0.0, 0.0, 0.0}; // gravity has no potential in a periodic box
    MdCoupling md = make_md(c);
    md.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL);
    const double h = 1e-6;
    auto energy = [&] {
      return md.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL, true).total();
    };
    // -dE/dx by central differences at the coordinate x (restored afterwards).
    auto minus_gradient = [&](double &x) {
      const double x0 = x;
      x = x0 + h;
      const double ep = energy();
      x = x0 - h;
      const double em = energy();
      x = x0;
      return -(ep - em) / (2 * h);
    };
    // every colloid coordinate
    for (std::size_t a = 0; a < 3; ++a)
      for (int k = 0; k < 2; ++k) {
        md.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL);
        const double f = fixed::to_double(md.colloid_force(a, k));
        EXPECT_NEAR(f, minus_gradient(c.colloids.x[k][a]), 1e-5 * (1.0 + std::abs(f)))
            << "colloid " << a << " axis " << k << " walls " << walls;
      }
    // fluid coordinates of the particles that feel a force
    int checked = 0;
    for (std::size_t i = 0; i < c.fluid.size(); ++i) {
      md.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL);
      if (md.fluid_force(i, 0) == 0 && md.fluid_force(i, 1) == 0)
        continue;
      ++checked;
      for (int k = 0; k < 2; ++k) {
        md.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL);
        const double f = fixed::to_double(md.fluid_force(i, k));
        EXPECT_NEAR(f, minus_gradient(c.fluid.x[k][i]), 1e-5 * (1.0 + std::abs(f)))
            << "fluid " << i;
      }
    }
    EXPECT_GT(checked, 10);
  }
}

TEST(ColloidForces, NewtonsThirdLawIsExactInFixedPoint) {
  // The fixed-point forces on all particles (fluid and colloids) along axis k.
  auto total = [](const Config &c, const MdCoupling &md, int k) {
    std::int64_t sum = 0;
    for (std::size_t i = 0; i < c.fluid.size(); ++i)
      sum += md.fluid_force(i, k);
    for (std::size_t a = 0; a < c.colloids.size(); ++a)
      sum += md.colloid_force(a, k);
    return sum;
  };
  // Periodic box, no gravity: they sum to exactly zero.
  Config c = make_config(false, 9);
  c.params.gravity = {0.0, 0.0, 0.0};
  MdCoupling md = make_md(c);
  md.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL);
  int nonzero = 0;
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(total(c, md, k), 0) << "axis " << k;
    for (std::size_t a = 0; a < 3; ++a)
      nonzero += md.colloid_force(a, k) != 0;
  }
  EXPECT_GT(nonzero, 0);
  // With gravity (a field: force M_a g on colloid a) the sum is exactly sum_a M_a g in fixed
  // point.
  c.params.gravity = {0.3, -0.1, 0.0};
  MdCoupling mg = make_md(c);
  mg.compute_forces(c.fluid, c.colloids, MPI_COMM_NULL);
  for (int k = 0; k < 2; ++k) {
    std::int64_t expected = 0;
    for (std::size_t a = 0; a < 3; ++a)
      expected += fixed::from_double(c.colloids.mass[a] * c.params.gravity[k]);
    EXPECT_EQ(total(c, mg, k), expected) << "axis " << k;
  }
}

TEST(ColloidPlacement, RandomKeepsColloidsApartAndOffTheWalls) {
  scene::Colloids spec;
  spec.radius = 1.5;
  spec.count = 12;
  spec.placement = scene::ColloidPlacement::random;
  mpcd::Box box = mpcd::make_periodic_box(2, {60, 12, 1});
  box.walls_y = true;
  const Colloids c = place_colloids(spec, box, 10.0, 77);
  ASSERT_EQ(c.size(), 12u);
  const double min_d = repulsive_cutoff(24, 3.0), margin = wall_cutoff(3.0);
  for (std::size_t a = 0; a < c.size(); ++a) {
    EXPECT_GE(c.x[1][a], margin);
    EXPECT_LE(c.x[1][a], 12.0 - margin);
    EXPECT_NEAR(c.mass[a], 3.14159265358979 * 2.25 * 10.0, 1e-9);
    for (std::size_t b = a + 1; b < c.size(); ++b) {
      const double dx = mpcd::wrap_periodic(c.x[0][a] - c.x[0][b] + 30.0, 60.0) - 30.0;
      EXPECT_GE(std::hypot(dx, c.x[1][a] - c.x[1][b]), min_d) << a << " " << b;
    }
  }
  // Fluid count excludes the colloids' area: n (V - N pi r^2).
  EXPECT_EQ(
      fluid_count_with_colloids(spec, box, 10.0),
      static_cast<std::uint64_t>(std::llround(10.0 * (720.0 - 12 * 3.14159265358979 * 2.25))));
  EXPECT_TRUE(inside_any(c, box, {c.x[0][0] + 1.0, c.x[1][0], 0.0}));
  EXPECT_FALSE(inside_any(c, box, {c.x[0][0] + 1.0, c.x[1][0] + 1.2, 0.0}));
}
