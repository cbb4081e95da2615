// Colloid potentials and MD forces: forces are minus gradients (finite differences), also with
// unequal radii, the wall potential's minimum is its cut-off, Newton's third law holds exactly
// in fixed point, the colloid cell list gives bitwise the forces of a double loop, radii drawn
// from a truncated Gaussian have its mean and spread, and the placement keeps colloids apart
// and fluid out of them.
#include "narrows/colloids/forces.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

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
  ForceParams params;
};

// Radii 2 (sigma_w = 4), or with `unequal` 2.1, 2.2, 2.0 and sigma_w = 2 r_a (the wall then
// pushes colloid 1).
Config make_config(bool walls, unsigned seed, bool unequal = false) {
  Config c;
  c.box = mpcd::make_periodic_box(2, {16, 10, 1});
  c.box.walls_y = walls;
  c.params.sigma_wall = unequal ? 0.0 : 4.0;
  c.params.gravity = {0.3, -0.1, 0.0};
  c.colloids.dim = 2;
  c.colloids.resize(3);
  const double pos[3][2] = {{3.0, 4.7}, {7.1, 5.4}, {14.9, 5.0}}; // 0-1 and 2-0 (periodic) overlap
  const double radius[3] = {2.1, 2.2, 2.0};
  for (int a = 0; a < 3; ++a) {
    c.colloids.x[0][a] = pos[a][0];
    c.colloids.x[1][a] = pos[a][1];
    c.colloids.mass[a] = 50.0 + 10.0 * a; // unequal, so gravity's M g is checked per colloid
    c.colloids.radius[a] = unequal ? radius[a] : 2.0;
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
      ok = ok && std::hypot(dx, p[1] - pos[a][1]) > 0.9 * c.colloids.radius[a];
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

ForceField make_md(const Config &c) { return ForceField(c.params, c.box); }

} // namespace

TEST(ColloidForces, AreMinusGradientsOfThePotentialEnergy) {
  for (const bool unequal : {false, true})
    for (const bool walls : {true, false}) {
      Config c = make_config(walls, 5, unequal);
      c.params.gravity = {0.0, 0.0, 0.0}; // gravity has no potential in a periodic box
      ForceField md = make_md(c);
      md.compute(c.fluid, c.colloids, MPI_COMM_NULL);
      const double h = 1e-6;
      auto energy = [&] { return md.compute(c.fluid, c.colloids, MPI_COMM_NULL, true).total(); };
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
          md.compute(c.fluid, c.colloids, MPI_COMM_NULL);
          const double f = fixed::to_double(md.colloid_force(a, k));
          EXPECT_NEAR(f, minus_gradient(c.colloids.x[k][a]), 1e-5 * (1.0 + std::abs(f)))
              << "colloid " << a << " axis " << k << " walls " << walls << " unequal " << unequal;
        }
      // fluid coordinates of the particles that feel a force
      int checked = 0;
      for (std::size_t i = 0; i < c.fluid.size(); ++i) {
        md.compute(c.fluid, c.colloids, MPI_COMM_NULL);
        if (md.fluid_force(i, 0) == 0 && md.fluid_force(i, 1) == 0)
          continue;
        ++checked;
        for (int k = 0; k < 2; ++k) {
          md.compute(c.fluid, c.colloids, MPI_COMM_NULL);
          const double f = fixed::to_double(md.fluid_force(i, k));
          EXPECT_NEAR(f, minus_gradient(c.fluid.x[k][i]), 1e-5 * (1.0 + std::abs(f)))
              << "fluid " << i << " unequal " << unequal;
        }
      }
      EXPECT_GT(checked, 10);
      if (unequal) { // every interaction of the unequal sizes takes part
        const auto e = md.compute(c.fluid, c.colloids, MPI_COMM_NULL, true);
        EXPECT_GT(e.colloid_colloid, 0.0);
        EXPECT_GT(e.colloid_fluid, 0.0);
        EXPECT_EQ(e.wall > 0.0, walls);
      }
    }
}

TEST(ColloidForces, NewtonsThirdLawIsExactInFixedPoint) {
  // The fixed-point forces on all particles (fluid and colloids) along axis k.
  auto total = [](const Config &c, const ForceField &md, int k) {
    std::int64_t sum = 0;
    for (std::size_t i = 0; i < c.fluid.size(); ++i)
      sum += md.fluid_force(i, k);
    for (std::size_t a = 0; a < c.colloids.size(); ++a)
      sum += md.colloid_force(a, k);
    return sum;
  };
  // Periodic box, no gravity: they sum to exactly zero (with equal and with unequal radii).
  for (const bool unequal : {false, true}) {
    Config u = make_config(false, 9, unequal);
    u.params.gravity = {0.0, 0.0, 0.0};
    ForceField mu = make_md(u);
    mu.compute(u.fluid, u.colloids, MPI_COMM_NULL);
    int nonzero = 0;
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(total(u, mu, k), 0) << "axis " << k << " unequal " << unequal;
      for (std::size_t a = 0; a < 3; ++a)
        nonzero += mu.colloid_force(a, k) != 0;
    }
    EXPECT_GT(nonzero, 0);
  }
  Config c = make_config(false, 9);
  // With gravity (a field: force M_a g on colloid a) the sum is exactly sum_a M_a g in fixed
  // point.
  c.params.gravity = {0.3, -0.1, 0.0};
  ForceField mg = make_md(c);
  mg.compute(c.fluid, c.colloids, MPI_COMM_NULL);
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
  const Colloids c = mpcd::place_colloids(spec, box, 10.0, 77);
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
      mpcd::fluid_count_with_colloids(spec, box, 10.0, 77),
      static_cast<std::uint64_t>(std::llround(10.0 * (720.0 - 12 * 3.14159265358979 * 2.25))));
  EXPECT_TRUE(inside_any(c, box, {c.x[0][0] + 1.0, c.x[1][0], 0.0}));
  EXPECT_FALSE(inside_any(c, box, {c.x[0][0] + 1.0, c.x[1][0] + 1.2, 0.0}));
}

TEST(ColloidPlacement, ListRefusesOverlappingCoresAndAllowsTouching) {
  scene::Colloids spec;
  spec.radius = 2.0;
  spec.placement = scene::ColloidPlacement::list;
  const mpcd::Box box = mpcd::make_periodic_box(2, {40, 12, 1});
  // Touching (centres r_a + r_b = 4 apart), also across the periodic edge: accepted.
  spec.positions = {{10.0, 6.0, 0}, {14.0, 6.0, 0}, {2.0, 6.0, 0}, {38.0, 6.0, 0}};
  spec.count = 4;
  EXPECT_EQ(mpcd::place_colloids(spec, box, 10.0, 77).size(), 4u);
  const auto refused = [&](const std::string &expect) {
    try {
      mpcd::place_colloids(spec, box, 10.0, 77);
    } catch (const narrows::Error &e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
      return true;
    }
    return false;
  };
  // Overlap across the periodic edge, the pair named by its entries.
  spec.position_keys = {"p[0]", "p[1]", "p[2]", "p[3]"};
  spec.positions[3] = {38.5, 6.5, 0};
  EXPECT_TRUE(refused("p[2] and p[3]: colloids 2 and 3 are 3.53553 apart"));
  // Overlap in y only (same x), with unequal radii from radius_sd.
  spec.positions = {{10.0, 3.0, 0}, {10.0, 6.9, 0}};
  spec.position_keys.clear();
  spec.count = 2;
  EXPECT_TRUE(refused("colloids.positions[0] and colloids.positions[1]"));
}

TEST(ColloidRadii, AreATruncatedGaussianDrawnPerColloid) {
  scene::Colloids spec;
  spec.radius = 2.0;
  EXPECT_EQ(mpcd::colloid_radius(spec, 5, 17), 2.0); // radius_sd = 0: all exactly radius
  spec.radius_sd = 0.2;
  constexpr int n = 10000;
  double sum = 0.0, sum2 = 0.0, lo = 1e9, hi = -1e9;
  int differ_by_seed = 0;
  for (int i = 0; i < n; ++i) {
    const double r = mpcd::colloid_radius(spec, 5, static_cast<std::uint64_t>(i));
    EXPECT_EQ(r, mpcd::colloid_radius(spec, 5, static_cast<std::uint64_t>(i))); // a pure function
    differ_by_seed += r != mpcd::colloid_radius(spec, 6, static_cast<std::uint64_t>(i));
    sum += r;
    sum2 += r * r;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  EXPECT_EQ(differ_by_seed, n);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  // A standard normal truncated at +-3 has variance 1 - 6 phi(3) / (2 Phi(3) - 1): sd 0.98658.
  const double pi = 3.14159265358979323846;
  const double phi3 = std::exp(-4.5) / std::sqrt(2.0 * pi), mass3 = std::erf(3.0 / std::sqrt(2.0));
  const double sd_truncated = 0.2 * std::sqrt(1.0 - 6.0 * phi3 / mass3);
  EXPECT_NEAR(sd_truncated / 0.2, 0.98658, 1e-5);
  // Standard errors: sd / sqrt(n) for the mean, about sd / sqrt(2 n) for the sd; 4 of them.
  EXPECT_NEAR(mean, 2.0, 4.0 * sd_truncated / std::sqrt(n));
  EXPECT_NEAR(sd, sd_truncated, 4.0 * sd_truncated / std::sqrt(2.0 * n));
  // Truncated at 3 sd, and the tails are reached (an untruncated Gaussian would put ~27 of
  // 10^4 beyond).
  EXPECT_GE(lo, 2.0 - 0.6);
  EXPECT_LE(hi, 2.0 + 0.6);
  EXPECT_LT(lo, 2.0 - 0.5);
  EXPECT_GT(hi, 2.0 + 0.5);
}

TEST(ColloidPlacement, UnequalRadiiSetMassesDistancesAndFluidCount) {
  scene::Colloids spec;
  spec.radius = 1.5;
  spec.radius_sd = 0.2;
  spec.count = 12;
  spec.placement = scene::ColloidPlacement::random;
  mpcd::Box box = mpcd::make_periodic_box(2, {60, 12, 1});
  box.walls_y = true;
  const Colloids c = mpcd::place_colloids(spec, box, 10.0, 77);
  ASSERT_EQ(c.size(), 12u);
  const double pi = 3.14159265358979323846;
  const double margin = wall_cutoff(2.0 * spec.max_radius()); // the largest wall cut-off
  double area = 0.0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    EXPECT_EQ(c.radius[a], mpcd::colloid_radius(spec, 77, a));
    EXPECT_NEAR(c.mass[a], pi * c.radius[a] * c.radius[a] * 10.0, 1e-9); // own area times n
    area += pi * c.radius[a] * c.radius[a];
    EXPECT_GE(c.x[1][a], margin);
    EXPECT_LE(c.x[1][a], 12.0 - margin);
    for (std::size_t b = a + 1; b < c.size(); ++b) {
      const double dx = mpcd::wrap_periodic(c.x[0][a] - c.x[0][b] + 30.0, 60.0) - 30.0;
      EXPECT_GE(std::hypot(dx, c.x[1][a] - c.x[1][b]),
                repulsive_cutoff(24, c.radius[a] + c.radius[b]))
          << a << " " << b;
    }
  }
  EXPECT_GT(*std::max_element(c.radius.begin(), c.radius.end()) -
                *std::min_element(c.radius.begin(), c.radius.end()),
            0.3);
  EXPECT_NEAR(static_cast<double>(mpcd::fluid_count_with_colloids(spec, box, 10.0, 77)),
              10.0 * (720.0 - area), 0.5 + 1e-9);
  // A fixed mass is every colloid's mass.
  spec.mass = 33.0;
  for (const double m : mpcd::place_colloids(spec, box, 10.0, 77).mass)
    EXPECT_EQ(m, 33.0);
}

namespace {

// The colloid-colloid and wall forces by a plain double loop over a < b (the reference the
// cell list must equal): fixed-point forces into `force` [a * dim + k], energy summed in that
// order; returns {colloid-colloid energy, wall energy}.
std::pair<double, double> double_loop_forces(const Colloids &c, const mpcd::Box &box, double eps,
                                             std::vector<std::int64_t> &force) {
  const int D = box.dim;
  const std::size_t n = c.size();
  force.assign(n * D, 0);
  double e_cc = 0.0, e_wall = 0.0;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      double d[3], r2 = 0.0;
      for (int k = 0; k < D; ++k) {
        d[k] = c.x[k][a] - c.x[k][b];
        const double L = box.length[k];
        if (!(k == 1 && box.walls_y))
          d[k] = d[k] > 0.5 * L ? d[k] - L : (d[k] < -0.5 * L ? d[k] + L : d[k]);
        r2 += d[k] * d[k];
      }
      const double s = c.radius[a] + c.radius[b];
      if (r2 >= std::pow(repulsive_cutoff(24, s), 2))
        continue;
      const PairTerm t = repulsive_pair<24>(r2, s * s, eps);
      e_cc += t.energy;
      for (int k = 0; k < D; ++k) {
        const std::int64_t q = fixed::from_double(t.f_over_r * d[k]);
        force[a * D + k] += q;
        force[b * D + k] -= q;
      }
    }
  if (box.walls_y)
    for (std::size_t a = 0; a < n; ++a) {
      const double sw = 2.0 * c.radius[a], y = c.x[1][a], Ly = box.length[1];
      if (y < wall_cutoff(sw)) {
        const WallTerm w = wall_term(y, sw, eps, 1.0);
        e_wall += w.energy;
        force[a * D + 1] += fixed::from_double(w.force);
      }
      if (Ly - y < wall_cutoff(sw)) {
        const WallTerm w = wall_term(Ly - y, sw, eps, 1.0);
        e_wall += w.energy;
        force[a * D + 1] -= fixed::from_double(w.force);
      }
    }
  return {e_cc, e_wall};
}

} // namespace

TEST(ColloidForces, CellListEqualsTheDoubleLoopBitwise) {
  // Boxes with many cells, and with axes of 1, 2 and 3 cells (largest cut-off 2^(1/24) 2.4 =
  // 2.47 for radii in [0.8, 1.2]), periodic and with walls, 2D and 3D.
  struct Box {
    int dim;
    std::array<int, 3> cells;
    bool walls;
    int count;
  };
  const Box boxes[] = {
      {2, {60, 40, 1}, false, 300}, {2, {60, 40, 1}, true, 300}, {3, {24, 16, 20}, false, 300},
      {3, {24, 16, 20}, true, 300}, {2, {60, 5, 1}, false, 60},  {2, {60, 8, 1}, true, 100},
      {2, {4, 60, 1}, false, 50},   {3, {30, 3, 5}, false, 40},  {3, {7, 8, 30}, true, 60}};
  std::mt19937_64 gen(2024);
  for (const Box &spec : boxes) {
    mpcd::Box box = mpcd::make_periodic_box(spec.dim, spec.cells);
    box.walls_y = spec.walls;
    Colloids c;
    c.dim = spec.dim;
    std::uniform_real_distribution<double> radius(0.8, 1.2);
    // Random positions; no pair closer than 0.9 sigma_cc (forces within the fixed-point range)
    // and no centre within 1 of a wall.
    for (int tries = 0; static_cast<int>(c.size()) < spec.count && tries < 100000; ++tries) {
      std::array<double, 3> p{0.0, 0.0, 0.0};
      for (int k = 0; k < spec.dim; ++k) {
        const double L = box.length[k];
        p[k] = k == 1 && spec.walls ? std::uniform_real_distribution<double>(1.0, L - 1.0)(gen)
                                    : std::uniform_real_distribution<double>(0.0, L)(gen);
      }
      const double r = radius(gen);
      bool ok = true;
      for (std::size_t b = 0; b < c.size() && ok; ++b) {
        double r2 = 0.0;
        for (int k = 0; k < spec.dim; ++k) {
          double d = p[k] - c.x[k][b];
          const double L = box.length[k];
          if (!(k == 1 && spec.walls))
            d = d > 0.5 * L ? d - L : (d < -0.5 * L ? d + L : d);
          r2 += d * d;
        }
        ok = r2 > std::pow(0.9 * (r + c.radius[b]), 2);
      }
      if (!ok)
        continue;
      const std::size_t a = c.size();
      c.resize(a + 1);
      for (int k = 0; k < spec.dim; ++k)
        c.x[k][a] = p[k];
      c.radius[a] = r;
      c.mass[a] = 1.0;
      c.id[a] = a;
    }
    ASSERT_EQ(static_cast<int>(c.size()), spec.count);
    ForceParams params;
    params.gravity = {0.0, 0.0, 0.0};
    ForceField md(params, box);
    mpcd::Fluid none;
    none.dim = spec.dim;
    const PotentialEnergy e = md.compute(none, c, MPI_COMM_NULL, true);
    std::vector<std::int64_t> ref;
    const auto [e_cc, e_wall] = double_loop_forces(c, box, params.epsilon, ref);
    std::size_t differ = 0, nonzero = 0;
    for (std::size_t a = 0; a < c.size(); ++a)
      for (int k = 0; k < spec.dim; ++k) {
        differ += md.colloid_force(a, k) != ref[a * spec.dim + k];
        nonzero += ref[a * spec.dim + k] != 0;
      }
    const std::string where = std::to_string(spec.dim) + "D " + std::to_string(spec.cells[0]) +
                              "x" + std::to_string(spec.cells[1]) + "x" +
                              std::to_string(spec.cells[2]) + (spec.walls ? " walls" : "");
    EXPECT_EQ(differ, 0u) << where;
    EXPECT_GT(nonzero, c.size() / 4) << where; // many pairs interact
    // The energy too, summed in the double loop's order.
    EXPECT_EQ(std::memcmp(&e.colloid_colloid, &e_cc, sizeof(double)), 0)
        << where << ": " << e.colloid_colloid << " vs " << e_cc;
    EXPECT_EQ(std::memcmp(&e.wall, &e_wall, sizeof(double)), 0) << where;
    EXPECT_GT(e_cc, 0.0) << where;
  }
}

// Several kinds: ids kind by kind with their radii and masses (density-matched unless given),
// random placement without any pair within its 48-24 cut-off and each kind off the walls by its
// own wall cut-off, the same placement on every call (every rank places all), and the fluid
// count excludes every colloid's area.
TEST(ColloidPlacement, SeveralKindsRandomWithoutOverlap) {
  scene::Colloids spec;
  spec.kinds = {{2.0, 0.0, 60}, {4.0, 900.0, 15}};
  spec.count = 75;
  spec.radius = 4.0;
  spec.placement = scene::ColloidPlacement::random;
  mpcd::Box box = mpcd::make_periodic_box(2, {120, 40, 1});
  box.walls_y = true;
  const double density = 10.0;
  const Colloids c = mpcd::place_colloids(spec, box, density, 3);
  ASSERT_EQ(c.size(), 75u);
  double area = 0.0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const bool large = a >= 60;
    EXPECT_EQ(c.id[a], a);
    EXPECT_DOUBLE_EQ(c.radius[a], large ? 4.0 : 2.0);
    EXPECT_NEAR(c.mass[a], large ? 900.0 : 3.14159265358979 * 4.0 * density, 1e-9);
    const double band = wall_cutoff(2.0 * c.radius[a]);
    EXPECT_GE(c.x[1][a], band) << a;
    EXPECT_LE(c.x[1][a], 40.0 - band) << a;
    area += 3.14159265358979 * c.radius[a] * c.radius[a];
    for (std::size_t b = a + 1; b < c.size(); ++b) {
      const double dx = mpcd::wrap_periodic(c.x[0][a] - c.x[0][b] + 60.0, 120.0) - 60.0;
      EXPECT_GE(std::hypot(dx, c.x[1][a] - c.x[1][b]),
                repulsive_cutoff(24, c.radius[a] + c.radius[b]))
          << a << " " << b;
    }
  }
  const Colloids again = mpcd::place_colloids(spec, box, density, 3);
  EXPECT_EQ(again.x[0], c.x[0]);
  EXPECT_EQ(again.x[1], c.x[1]);
  EXPECT_NE(mpcd::place_colloids(spec, box, density, 4).x[0], c.x[0]); // the seed decides
  EXPECT_EQ(mpcd::fluid_count_with_colloids(spec, box, density, 3),
            static_cast<std::uint64_t>(std::llround(density * (4800.0 - area))));
}
