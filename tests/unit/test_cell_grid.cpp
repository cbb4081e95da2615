// The shifted collision grid: grid_shift, bin_particles against an independent floor/modulo
// computation with fixed-point cell sums, and the stable counting sort by cell.
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/cell_sort.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <numeric>
#include <random>
#include <set>
#include <vector>

namespace {

using namespace narrows;
using namespace narrows::mpcd;

Box make_box(int dim, std::array<int, 3> cells) { return make_periodic_box(dim, cells); }

// Random fluid with shuffled unique ids; includes x = 0 and x just below L on every axis.
Fluid random_fluid(const Box &box, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), uv(-4.0, 4.0);
  Fluid f;
  f.dim = box.dim;
  f.resize(n);
  std::vector<std::uint64_t> ids(n);
  std::iota(ids.begin(), ids.end(), 1000);
  std::shuffle(ids.begin(), ids.end(), gen);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = ids[i];
    for (int k = 0; k < box.dim; ++k) {
      const double L = box.length[k];
      double x = u(gen) * L;
      if (i % 97 == 0)
        x = 0.0;
      if (i % 97 == 1)
        x = std::nextafter(L, 0.0);
      if (i % 97 == 2)
        x = std::floor(x); // exactly on an unshifted cell boundary
      f.x[k][i] = x;
      f.v[k][i] = uv(gen);
    }
  }
  if (box.dim == 2)
    f.x[2].assign(n, 0.0); // for printing only: the 2D kernel never reads z
  return f;
}

// Independent reference: floor(x - s) wrapped periodically with an integer modulo.
std::uint32_t ref_cell(const Fluid &f, const CellGrid &g, std::size_t i) {
  std::uint64_t c = 0, stride = 1;
  for (int k = 0; k < g.dim; ++k) {
    const long long n = g.cells[k];
    const long long j = static_cast<long long>(std::floor(f.x[k][i] - g.shift[k]));
    c += stride * static_cast<std::uint64_t>(((j % n) + n) % n);
    stride *= static_cast<std::uint64_t>(n);
  }
  return static_cast<std::uint32_t>(c);
}

TEST(GridShift, RangeDeterminismAndStepDependence) {
  for (int dim : {2, 3})
    for (std::uint64_t seed : {0ull, 1ull, 77ull, 0xdeadbeefcafef00dull}) {
      std::set<std::array<double, 3>> seen;
      for (std::uint64_t step = 0; step < 2000; ++step) {
        const auto s = grid_shift(seed, step, dim);
        for (int k = 0; k < dim; ++k) {
          ASSERT_GE(s[k], -0.5) << "seed " << seed << " step " << step << " axis " << k;
          ASSERT_LT(s[k], 0.5) << "seed " << seed << " step " << step << " axis " << k;
        }
        if (dim == 2) {
          ASSERT_EQ(s[2], 0.0) << "z shift must be 0 in 2D";
        }
        ASSERT_EQ(s, grid_shift(seed, step, dim)) << "same (seed, step) must give same shift";
        seen.insert(s);
      }
      EXPECT_EQ(seen.size(), 2000u) << "shifts repeat between steps, seed " << seed;
      EXPECT_NE(grid_shift(seed, 5, dim), grid_shift(seed + 1, 5, dim));
      EXPECT_NE(grid_shift(seed, 5, dim), grid_shift(seed, 5 + (1ull << 32), dim));
    }
}

TEST(GridShift, UniformMeanAndVariance) {
  // Over N steps each component has mean 0 and variance 1/12: sigma of the mean
  // sqrt(1/(12 N)), of the second moment sqrt(1/(180 N)) (Var(u^2) = 1/80 - 1/144 = 1/180).
  const int N = 100000;
  double m[3] = {0, 0, 0}, q[3] = {0, 0, 0};
  for (int step = 0; step < N; ++step) {
    const auto s = grid_shift(42, step, 3);
    for (int k = 0; k < 3; ++k) {
      m[k] += s[k];
      q[k] += s[k] * s[k];
    }
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(m[k] / N), 5 * std::sqrt(1.0 / (12.0 * N))) << "axis " << k;
    EXPECT_LT(std::abs(q[k] / N - 1.0 / 12), 5 * std::sqrt(1.0 / (180.0 * N))) << "axis " << k;
  }
}

void check_binning(const Box &box, const std::array<double, 3> &shift, std::uint64_t seed) {
  Fluid f = random_fluid(box, 6000, seed);
  const Fluid before = f;
  CellGrid g(box);
  ASSERT_EQ(g.size(), box.num_cells());
  g.shift = shift;
  bin_particles(f, g);
  std::vector<std::uint32_t> count(g.size(), 0);
  std::vector<std::array<std::int64_t, 3>> p(g.size(), {0, 0, 0});
  for (std::size_t i = 0; i < f.size(); ++i) {
    const std::uint32_t want = ref_cell(f, g, i);
    ASSERT_EQ(f.cell[i], want) << "particle " << i << std::setprecision(17) << " x " << f.x[0][i]
                               << " y " << f.x[1][i] << " z " << f.x[2][i] << " shift " << shift[0]
                               << " " << shift[1] << " " << shift[2]
                               << " (if a coordinate is one ulp below a shifted cell boundary "
                                  "this is the library bug of GridBin.UlpBelowCellBoundary)";
    ++count[want];
    for (int k = 0; k < box.dim; ++k)
      p[want][k] += fixed::from_double(f.v[k][i]);
  }
  std::uint64_t total = 0;
  for (std::size_t c = 0; c < g.size(); ++c) {
    EXPECT_EQ(g.sums[c].n, count[c]) << "cell " << c;
    total += g.sums[c].n;
    for (int k = 0; k < 3; ++k) // exact integer sums; z stays 0 in 2D
      EXPECT_EQ(g.sums[c].p[k], p[c][k]) << "cell " << c << " axis " << k;
  }
  EXPECT_EQ(total, f.size());
  // Binning touches only cell[].
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(f.x[k], before.x[k]);
    EXPECT_EQ(f.v[k], before.v[k]);
  }
  EXPECT_EQ(f.id, before.id);
  // Rebinning resets the sums rather than accumulating.
  bin_particles(f, g);
  std::uint64_t again = 0;
  for (const auto &s : g.sums)
    again += s.n;
  EXPECT_EQ(again, f.size());
}

TEST(GridBin, MatchesFloorModulo2D) {
  const Box box = make_box(2, {13, 7, 1});
  for (const auto &s : std::vector<std::array<double, 3>>{
           {0.0, 0.0, 0.0}, {0.3217, -0.4, 0.0}, {-0.5, 0.4999999, 0.0}, {-0.123, -0.001, 0.0}})
    check_binning(box, s, 3);
  for (std::uint64_t step = 0; step < 20; ++step)
    check_binning(box, grid_shift(9, step, 2), step);
}

TEST(GridBin, MatchesFloorModulo3D) {
  const Box box = make_box(3, {5, 9, 4});
  for (const auto &s : std::vector<std::array<double, 3>>{
           {0.0, 0.0, 0.0}, {0.3217, -0.4, 0.25}, {-0.5, 0.4999999, -0.3}, {0.1, 0.2, -0.001}})
    check_binning(box, s, 4);
  for (std::uint64_t step = 0; step < 20; ++step)
    check_binning(box, grid_shift(10, step, 3), step);
}

TEST(GridBin, OneCellPerAxisAndEmptyFluid) {
  const Box box = make_box(3, {1, 1, 1});
  check_binning(box, {0.4, -0.4, 0.0}, 1);
  Fluid f;
  f.dim = 3;
  f.resize(0);
  CellGrid g(box);
  bin_particles(f, g);
  EXPECT_EQ(g.sums[0].n, 0u);
}

// Positions one ulp below a shifted cell boundary, where x - s lies within half an ulp of an
// integer: floor(x - s) is the lower cell. These are exact inputs (x - s is computed exactly),
// so the cell is unambiguous.
TEST(GridBin, UlpBelowCellBoundary) {
  const Box box = make_box(2, {8, 8, 1});
  CellGrid g(box);
  for (double s : {0.0, 0.25, -0.25, -0.5}) {
    g.shift = {s, s, 0.0};
    Fluid f;
    f.dim = 2;
    f.resize(8);
    for (int m = 0; m < 8; ++m) {
      f.id[m] = m;
      // The boundary m + s (in [0, L)), approached from below; wrap m + s < 0 to the top.
      double b = m + s;
      if (b <= 0.0)
        b += box.length[0];
      const double x = std::nextafter(b, 0.0);
      f.x[0][m] = x;
      f.x[1][m] = 0.5 + s + 1.0; // safely inside row 1
      f.v[0][m] = f.v[1][m] = 0.0;
    }
    bin_particles(f, g);
    for (std::size_t i = 0; i < f.size(); ++i)
      EXPECT_EQ(f.cell[i], ref_cell(f, g, i))
          << "LIBRARY BUG (src/engines/mpcd/kernels/cell_grid.cpp, cell_coordinate): x = "
          << std::setprecision(17) << f.x[0][i] << " (one ulp below the boundary), shift " << s
          << ": floor(x - s) = " << std::floor(f.x[0][i] - s) << " (exact), but bin_particles "
          << "gives column " << f.cell[i] % 8
          << " because (int)(x - s + 1.0) - 1 rounds x - s + 1.0 up to the next integer";
  }
}

void check_sort(const Box &box, std::uint64_t seed) {
  Fluid f = random_fluid(box, 5000, seed);
  CellGrid g(box);
  g.shift = grid_shift(seed, 1, box.dim);
  bin_particles(f, g);
  const Fluid before = f;
  // id -> original index
  std::vector<std::size_t> where(before.size() + 1000);
  for (std::size_t i = 0; i < before.size(); ++i)
    where[before.id[i] - 1000] = i;
  SortScratch scratch;
  sort_by_cell(f, g, scratch);
  ASSERT_EQ(f.size(), before.size());
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(f.x[k].size(), before.x[k].size());
    ASSERT_EQ(f.v[k].size(), before.v[k].size());
  }
  ASSERT_EQ(f.cell.size(), before.cell.size());
  std::vector<bool> hit(before.size(), false);
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (i > 0) {
      ASSERT_LE(f.cell[i - 1], f.cell[i]) << "cell[] not sorted at " << i;
    }
    const std::size_t o = where[f.id[i] - 1000];
    ASSERT_FALSE(hit[o]) << "id " << f.id[i] << " appears twice";
    hit[o] = true;
    ASSERT_EQ(f.cell[i], before.cell[o]) << "id " << f.id[i];
    for (int k = 0; k < box.dim; ++k) {
      ASSERT_EQ(f.x[k][i], before.x[k][o]) << "id " << f.id[i] << " axis " << k;
      ASSERT_EQ(f.v[k][i], before.v[k][o]) << "id " << f.id[i] << " axis " << k;
    }
    // Stable: within a cell the original order is kept.
    if (i > 0 && f.cell[i - 1] == f.cell[i]) {
      ASSERT_LT(where[f.id[i - 1] - 1000], o) << "not stable in cell " << f.cell[i];
    }
  }
  // Cell blocks start where the prefix sums of the counts say.
  std::size_t start = 0;
  for (std::size_t c = 0; c < g.size(); ++c) {
    for (std::size_t j = start; j < start + g.sums[c].n; ++j)
      ASSERT_EQ(f.cell[j], c);
    start += g.sums[c].n;
  }
  // Sorting again (scratch reused) is the identity.
  const Fluid sorted = f;
  sort_by_cell(f, g, scratch);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(f.x[k], sorted.x[k]);
    EXPECT_EQ(f.v[k], sorted.v[k]);
  }
  EXPECT_EQ(f.id, sorted.id);
  EXPECT_EQ(f.cell, sorted.cell);
}

TEST(SortByCell, Permutation2D) { check_sort(make_box(2, {11, 6, 1}), 21); }
TEST(SortByCell, Permutation3D) { check_sort(make_box(3, {6, 5, 7}), 22); }

} // namespace

// A coordinate no cell can hold (NaN, infinite, far outside the box) is a broken invariant
// naming the particle, never an index out of the cell arrays (issue 18).
TEST(GridBin, UnplaceableCoordinateIsAnInvariantError) {
  for (const bool walls : {false, true})
    for (int axis = 0; axis < 3; ++axis)
      for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL, 1e300, -1e300, 40.0}) {
        Box box = make_box(3, {8, 8, 8});
        box.walls_y = walls;
        CellGrid g(box);
        Fluid f;
        f.dim = 3;
        f.resize(3);
        for (int i = 0; i < 3; ++i) {
          f.id[i] = 10 + i;
          for (int k = 0; k < 3; ++k)
            f.x[k][i] = 1.5 + i, f.v[k][i] = 0.0;
        }
        f.x[axis][1] = bad;
        try {
          bin_particles(f, g);
          ADD_FAILURE() << "no error for coordinate " << axis << " = " << bad;
        } catch (const Error &e) {
          EXPECT_EQ(e.code(), ExitCode::invariant);
          const std::string msg = e.what();
          EXPECT_NE(msg.find("fluid particle id 11"), std::string::npos) << msg;
          EXPECT_NE(msg.find("coordinate " + std::to_string(axis)), std::string::npos) << msg;
        }
      }
}

TEST(CellList, ClampedCellGuardsNonFiniteAndFarCoordinates) {
  EXPECT_EQ(clamped_cell(0.0, 0.5, 4, "colloid", 1, 0), 0);
  EXPECT_EQ(clamped_cell(-0.3, 0.5, 4, "colloid", 1, 0), 0);
  EXPECT_EQ(clamped_cell(8.0, 0.5, 4, "colloid", 1, 0), 3);
  EXPECT_EQ(clamped_cell(5.9, 0.5, 4, "colloid", 1, 0), 2);
  for (const double bad : {std::nan(""), HUGE_VAL, -1e300, 16.0, -8.0})
    EXPECT_THROW(clamped_cell(bad, 0.5, 4, "colloid", 7, 1), Error) << bad;
}

// A slab's grid (columns 5 to 12 of 20): particles whose shifted column lies outside it are
// listed as strays in the order of the particles, with their global column, and left out of
// every cell sum; the others get their cell in the slab. Without a strays list the first of
// them (in particle order, here beyond the first block of 256 the binning works in) is named.
// Particles in blocks are binned branch-free and a block with a stray is gone through again, so
// strays at the start, inside and at the end of blocks, and a block of only strays, are mixed.
TEST(GridBin, SlabListsStraysInOrder) {
  for (const int dim : {2, 3}) {
    const Box box = make_box(dim, {20, 6, 4});
    const int first = 5, columns = 8;
    CellGrid g(box, first, columns);
    g.shift = {0.3, -0.2, 0.1};
    Fluid f = random_fluid(box, 1500, 7 + dim);
    for (std::size_t i = 512; i < 768; ++i) // a whole block of strays
      f.x[0][i] = 1.5;
    std::vector<std::size_t> want;
    std::vector<int> want_column;
    std::uint64_t inside = 0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int column = static_cast<int>(
          ((static_cast<long long>(std::floor(f.x[0][i] - g.shift[0])) % 20) + 20) % 20);
      if (column < first || column >= first + columns) {
        want.push_back(i);
        want_column.push_back(column);
      } else {
        ++inside;
      }
    }
    ASSERT_GT(want.size(), 300u);
    ASSERT_GT(inside, 300u);
    Strays strays;
    bin_particles(f, g, &strays);
    EXPECT_EQ(strays.index, want);
    EXPECT_EQ(strays.column, want_column);
    std::uint64_t binned = 0;
    for (const auto &s : g.sums)
      binned += s.n;
    EXPECT_EQ(binned, inside);
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (std::find(want.begin(), want.end(), i) != want.end())
        continue;
      Fluid one = f; // the reference cell in the slab: the column less the slab's first
      one.x[0][i] = f.x[0][i] - first;
      CellGrid local(make_box(dim, {columns, 6, 4}));
      local.shift = g.shift;
      ASSERT_EQ(f.cell[i], ref_cell(one, local, i)) << "dim " << dim << " particle " << i;
    }
    // Without a list: the first stray beyond the first block is named (the earlier ones moved in).
    for (std::size_t k = 0; k < want.size() && want[k] < 300; ++k)
      f.x[0][want[k]] = first + 3.5;
    const std::size_t named =
        *std::find_if(want.begin(), want.end(), [](std::size_t i) { return i >= 300; });
    try {
      bin_particles(f, g);
      ADD_FAILURE() << "no error for a particle beyond the slab";
    } catch (const Error &e) {
      EXPECT_EQ(e.code(), ExitCode::invariant);
      const std::string msg = e.what();
      EXPECT_NE(msg.find("particle id " + std::to_string(f.id[named]) + " at x"), std::string::npos)
          << msg;
      EXPECT_NE(msg.find("outside this rank's slab (columns 5 to 12)"), std::string::npos) << msg;
    }
  }
}
