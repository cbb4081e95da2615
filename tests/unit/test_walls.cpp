// Walls: exact hit times, bounce-back and specular streaming (exact single hits, time
// reversibility, energy, never outside, hard cases), wall rows of the grid, virtual particles.
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/engines/mpcd/walls/bounce_back.hpp"
#include "narrows/engines/mpcd/walls/virtual_particles.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using namespace narrows;
using mpcd::Box;
using mpcd::Fluid;

Box channel(int dim, std::array<int, 3> cells) {
  Box b = mpcd::make_periodic_box(dim, cells);
  b.walls_y = true;
  return b;
}

Fluid random_fluid(const Box &box, std::size_t n, double speed, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, speed);
  Fluid f;
  f.dim = box.dim;
  f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = i;
    for (int k = 0; k < box.dim; ++k) {
      f.x[k][i] = u(gen) * box.length[k];
      f.v[k][i] = g(gen);
    }
  }
  return f;
}

// Brute force: the first time in (t_prev, T] at which h + u t + a t^2/2 crosses zero going
// outward, by fine scanning and bisection.
double brute_time_to_wall(double h, double u, double a, double T) {
  auto pos = [&](double t) { return h + u * t + 0.5 * a * t * t; };
  const int n = 200000;
  double prev = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double t = T * i / n;
    if (pos(t) < 0.0) {
      double lo = prev, hi = t;
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (pos(mid) < 0.0 ? hi : lo) = mid;
      }
      return 0.5 * (lo + hi);
    }
    prev = t;
  }
  return std::numeric_limits<double>::infinity();
}

TEST(TimeToWall, MatchesBruteForce) {
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> h(0.0, 1.0), u(-2.0, 2.0), a(-5.0, 5.0);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const double hh = h(gen), uu = u(gen), aa = i % 4 == 0 ? 0.0 : a(gen);
    const double t = walls::time_to_wall(hh, uu, aa);
    const double ref = brute_time_to_wall(hh, uu, aa, 2.0);
    if (std::isinf(ref)) {
      EXPECT_TRUE(t > 2.0 - 1e-4) << hh << " " << uu << " " << aa << " -> " << t;
    } else {
      ++hits;
      EXPECT_NEAR(t, ref, 1e-4) << hh << " " << uu << " " << aa;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST(TimeToWall, SpecialCases) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(walls::time_to_wall(0.0, -1.0, 0.0), 0.0);        // on the wall, moving out: now
  EXPECT_EQ(walls::time_to_wall(0.0, 1.0, 0.0), inf);         // on the wall, moving in
  EXPECT_EQ(walls::time_to_wall(0.0, 0.0, 0.0), inf);         // at rest on the wall
  EXPECT_EQ(walls::time_to_wall(0.0, 0.0, -1.0), 0.0);        // at rest, pulled out
  EXPECT_EQ(walls::time_to_wall(0.0, 0.0, 1.0), inf);         // at rest, pushed in
  EXPECT_DOUBLE_EQ(walls::time_to_wall(0.0, 2.0, -1.0), 4.0); // up and back down
  EXPECT_DOUBLE_EQ(walls::time_to_wall(0.5, -0.25, 0.0), 2.0);
  EXPECT_EQ(walls::time_to_wall(1.0, -1.0, 4.0), inf); // turns back at h = 7/8
  // Tiny force: no cancellation (the exact root of 1 - t + 1e-12 t^2/2 is 1 + 5e-13 + ...).
  EXPECT_NEAR(walls::time_to_wall(1.0, -1.0, 1e-12), 1.0 + 5e-13, 1e-15);
}

TEST(StreamChannel, SingleNoSlipHitUnderForceIsExact) {
  // y0 = 0.05, v = (0.3, -1): hits y = 0 at t_c = 0.05 (g has no y part); there v_x =
  // 0.3 + g t_c; bounce-back reverses both components; the rest of the step (0.05) is flown
  // with the force again.
  const Box box = channel(2, {20, 10, 1});
  Fluid f;
  f.dim = 2;
  f.resize(1);
  f.x[0][0] = 5.0;
  f.x[1][0] = 0.05;
  f.v[0][0] = 0.3;
  f.v[1][0] = -1.0;
  const double g = 0.01, dt = 0.1, tc = 0.05, rest = dt - tc;
  walls::stream_channel(f, box, dt, {g, 0.0, 0.0}, false);
  const double xc = 5.0 + 0.3 * tc + 0.5 * g * tc * tc, vxc = 0.3 + g * tc;
  EXPECT_NEAR(f.x[0][0], xc - vxc * rest + 0.5 * g * rest * rest, 1e-15);
  EXPECT_NEAR(f.x[1][0], 1.0 * rest, 1e-15);
  EXPECT_NEAR(f.v[0][0], -vxc + g * rest, 1e-15);
  EXPECT_NEAR(f.v[1][0], 1.0, 1e-15);

  // Specular: only v_y reverses.
  f.x[0][0] = 5.0;
  f.x[1][0] = 0.05;
  f.v[0][0] = 0.3;
  f.v[1][0] = -1.0;
  walls::stream_channel(f, box, dt, {g, 0.0, 0.0}, true);
  EXPECT_NEAR(f.x[0][0], 5.0 + 0.3 * dt + 0.5 * g * dt * dt, 1e-15);
  EXPECT_NEAR(f.v[0][0], 0.3 + g * dt, 1e-15);
  EXPECT_NEAR(f.x[1][0], 1.0 * rest, 1e-15);
}

// Bounce-back and specular reflection are time reversible, also under a constant force:
// flying dt, reversing every velocity and flying dt again returns every particle to its start.
TEST(StreamChannel, TimeReversibleWithForceAndManyHits) {
  for (int dim : {2, 3})
    for (bool slip : {false, true}) {
      const Box box = channel(dim, {1000, 3, 1000});
      Fluid f = random_fluid(box, 4000, 3.0, 7 + dim);
      const Fluid start = f;
      const std::array<double, 3> g{0.3, -0.7, 0.2};
      const double dt = 0.8; // |v| dt ~ L_y: several hits per step
      walls::stream_channel(f, box, dt, g, slip);
      for (int k = 0; k < dim; ++k)
        for (double &v : f.v[k])
          v = -v;
      walls::stream_channel(f, box, dt, g, slip);
      double worst = 0.0;
      for (int k = 0; k < dim; ++k)
        for (std::size_t i = 0; i < f.size(); ++i) {
          worst = std::max(worst, std::abs(f.x[k][i] - start.x[k][i]));
          worst = std::max(worst, std::abs(f.v[k][i] + start.v[k][i]));
        }
      EXPECT_LT(worst, 1e-9) << "dim " << dim << " slip " << slip;
    }
}

// |v|^2/2 - g.x is conserved through every hit (reversal keeps |v|, x is continuous).
TEST(StreamChannel, EnergyConservedThroughHits) {
  const Box box = channel(3, {4000, 4, 4000});
  Fluid f = random_fluid(box, 3000, 2.0, 11);
  for (std::size_t i = 0; i < f.size(); ++i) { // away from the periodic seams
    f.x[0][i] = 2000.0;
    f.x[2][i] = 2000.0;
  }
  const std::array<double, 3> g{0.5, 0.9, -0.4};
  auto energy = [&](std::size_t i) {
    double e = 0.0;
    for (int k = 0; k < 3; ++k)
      e += 0.5 * f.v[k][i] * f.v[k][i] - g[k] * f.x[k][i];
    return e;
  };
  std::vector<double> e0(f.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    e0[i] = energy(i);
  for (int step = 0; step < 20; ++step)
    walls::stream_channel(f, box, 0.5, g, false);
  for (std::size_t i = 0; i < f.size(); ++i)
    ASSERT_NEAR(energy(i), e0[i], 1e-9 * (1.0 + std::abs(e0[i]))) << "particle " << i;
}

// Hard cases: particles exactly on the walls, at rest on them, a strong force pressing them
// into a wall, a narrow channel crossed many times per step: nobody ends outside, no NaN.
TEST(StreamChannel, NeverOutsideInHardCases) {
  const Box box = channel(2, {16, 2, 1});
  Fluid f = random_fluid(box, 3000, 5.0, 5);
  for (std::size_t i = 0; i < f.size(); i += 3)
    f.x[1][i] = (i % 2) ? 0.0 : box.length[1];
  for (std::size_t i = 0; i < f.size(); i += 7) {
    f.x[1][i] = 0.0;
    f.v[1][i] = 0.0;
  }
  for (const std::array<double, 3> g :
       {std::array<double, 3>{0.0, -50.0, 0.0}, std::array<double, 3>{2.0, 50.0, 0.0},
        std::array<double, 3>{0.0, 0.0, 0.0}})
    for (int step = 0; step < 200; ++step) {
      walls::stream_channel(f, box, 0.5, g, step % 2 == 0);
      for (std::size_t i = 0; i < f.size(); ++i) {
        ASSERT_TRUE(f.x[1][i] >= 0.0 && f.x[1][i] <= box.length[1]) << f.x[1][i];
        ASSERT_TRUE(f.x[0][i] >= 0.0 && f.x[0][i] < box.length[0]) << f.x[0][i];
        ASSERT_TRUE(std::isfinite(f.v[0][i]) && std::isfinite(f.v[1][i]));
      }
    }
}

TEST(WallGrid, RowsCoverTheChannel) {
  const Box box = channel(2, {4, 5, 1});
  mpcd::CellGrid g(box);
  EXPECT_EQ(g.cells[1], 6); // L_y + 1 rows
  g.set_shift({0.1, -0.5, 0.0});
  EXPECT_DOUBLE_EQ(g.shift[1], 0.0);
  g.set_shift({0.1, 0.25, 0.0});
  EXPECT_DOUBLE_EQ(g.shift[1], 0.75);
  // Row j covers [j - 1 + s, j + s).
  EXPECT_EQ(mpcd::wall_row(0.0, 0.75, 6), 0);
  EXPECT_EQ(mpcd::wall_row(0.74, 0.75, 6), 0);
  EXPECT_EQ(mpcd::wall_row(0.75, 0.75, 6), 1);
  EXPECT_EQ(mpcd::wall_row(5.0, 0.75, 6), 5);
  EXPECT_EQ(mpcd::wall_row(0.0, 0.0, 6), 1);
  EXPECT_EQ(mpcd::wall_row(5.0, 0.0, 6), 5); // on the upper wall with s = 0: the last row
  // A particle near y = 0 and one near y = L_y never share a cell.
  Fluid f;
  f.dim = 2;
  f.resize(2);
  f.x[0] = {1.5, 1.5};
  f.x[1] = {0.1, 4.95};
  f.v[0] = {0.0, 0.0};
  f.v[1] = {0.0, 0.0};
  for (double s : {-0.5, -0.2, 0.0, 0.3, 0.49}) {
    g.set_shift({0.0, s, 0.0});
    mpcd::bin_particles(f, g);
    EXPECT_NE(f.cell[0], f.cell[1]) << s;
  }
}

TEST(VirtualParticles, FillCutCellsWithTheRightStatistics) {
  const Box box = channel(3, {6, 4, 5});
  mpcd::CellGrid g(box);
  Fluid f = random_fluid(box, 6 * 4 * 5 * 8, 1.0, 9);
  const double density = 8.0, kT = 1.7;
  double chi = 0.0;
  long draws = 0;
  for (std::uint64_t step = 0; step < 200; ++step) {
    g.set_shift(mpcd::grid_shift(5, step, 3));
    mpcd::bin_particles(f, g);
    walls::add_virtual_particles(g, density, kT, 5, step, true);
    for (const auto &v : g.virtual_cells) {
      const int row = static_cast<int>(v.cell / g.cells[0]) % g.cells[1];
      ASSERT_TRUE(row == 0 || row == g.cells[1] - 1) << row;
      ASSERT_DOUBLE_EQ(v.count, density - g.sums[v.cell].n);
      for (int k = 0; k < 3; ++k) {
        chi += v.momentum[k] * v.momentum[k] / (v.count * kT);
        chi += v.noise[k] * v.noise[k] / (v.count * kT);
        draws += 2;
      }
    }
  }
  // Each term is chi-square with one degree of freedom (variance 2): the mean is 1 within
  // 5 standard errors.
  ASSERT_GT(draws, 10000);
  EXPECT_NEAR(chi / draws, 1.0, 5.0 * std::sqrt(2.0 / draws));
}

// In a cut cell the SRD mean velocity includes the virtual particles: with the rotation
// R, the real particles' momentum after the collision is n u + R (P - n u), u = (P + P_v)/n_f.
TEST(VirtualParticles, SrdUsesTheirMomentum) {
  const Box box = channel(2, {3, 3, 1});
  mpcd::CellGrid g(box);
  Fluid f = random_fluid(box, 40, 1.0, 21);
  for (std::size_t i = 0; i < f.size(); ++i)
    f.x[1][i] = 0.02 * static_cast<double>(i % 10); // all within the lowest cut row
  g.set_shift({0.0, 0.3, 0.0});                     // y shift 0.8: row 0 covers [0, 0.8)
  mpcd::bin_particles(f, g);
  walls::add_virtual_particles(g, 30.0, 1.0, 4, 2, false);
  ASSERT_FALSE(g.virtual_cells.empty());
  std::vector<std::array<double, 2>> before(g.size(), {0.0, 0.0});
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 2; ++k)
      before[f.cell[i]][k] += f.v[k][i];
  mpcd::CollisionScratch scratch;
  const double angle = 2.0;
  mpcd::collide_srd(f, g, scratch, angle, 4, 2);
  std::vector<std::array<double, 2>> after(g.size(), {0.0, 0.0});
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 2; ++k)
      after[f.cell[i]][k] += f.v[k][i];
  for (const auto &v : g.virtual_cells) {
    const double n = g.sums[v.cell].n;
    if (n == 0)
      continue;
    const auto &P = before[v.cell];
    const double ux = (P[0] + v.momentum[0]) / 30.0, uy = (P[1] + v.momentum[1]) / 30.0;
    const double wx = P[0] - n * ux, wy = P[1] - n * uy;
    // The rotation sign is random per cell: one of the two must match.
    bool match = false;
    for (double s : {1.0, -1.0}) {
      const double c = std::cos(angle), sn = s * std::sin(angle);
      const double ex = n * ux + c * wx - sn * wy, ey = n * uy + sn * wx + c * wy;
      match |= std::abs(after[v.cell][0] - ex) < 1e-9 && std::abs(after[v.cell][1] - ey) < 1e-9;
    }
    EXPECT_TRUE(match) << "cell " << v.cell;
  }
}

} // namespace

namespace {

// With the mirror option and kT = 0, the virtual particles continue a linear profile
// v_x = gamma y antisymmetrically through the wall: the cut cell's mean velocity becomes the
// average of gamma y over the whole cell, gamma (s - 1/2) for the lower wall (fluid part
// [0, s)), and likewise at the upper wall.
TEST(VirtualParticles, MirrorContinuesALinearProfile) {
  const Box box = channel(2, {2, 6, 1});
  const double gamma = 0.01, L = box.length[1];
  const int per_row = 1000; // particles on a fine lattice: the averages are near exact
  Fluid f;
  f.dim = 2;
  f.resize(static_cast<std::size_t>(2 * 6 * per_row));
  for (std::size_t i = 0; i < f.size(); ++i) {
    f.id[i] = i;
    f.x[0][i] = 0.5 + (i % 2);
    f.x[1][i] = (static_cast<double>(i / 2) + 0.5) * L / (f.size() / 2);
    f.v[0][i] = gamma * std::min(f.x[1][i], L - f.x[1][i]); // both walls at rest
    f.v[1][i] = 0.0;
  }
  for (double shift : {-0.4, -0.1, 0.2, 0.45}) {
    mpcd::CellGrid g(box);
    g.set_shift({0.0, shift, 0.0});
    mpcd::bin_particles(f, g);
    const double density = f.size() / (2.0 * L); // particles per unit cell
    walls::add_virtual_particles(g, density, 0.0, 1, 1, false, true);
    for (const auto &v : g.virtual_cells) {
      const std::size_t row = (v.cell / 2) % g.cells[1];
      const double s = row == 0 ? g.shift[1] : 1.0 - g.shift[1];
      const double mean =
          (fixed::to_double(g.sums[v.cell].p[0]) + v.momentum[0]) / (g.sums[v.cell].n + v.count);
      EXPECT_NEAR(mean, gamma * (s - 0.5), 2e-3 * gamma) << "shift " << shift << " row " << row;
    }
  }
}

} // namespace
