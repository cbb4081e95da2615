// Particle groups (grid.groups: particles known only by their sums, the no-slip colloids'
// ghosts) collide as their particles would: random cells, some of whose particles are taken out
// of the fluid and handed to the rule as two groups per cell (their count, moments, velocities and
// the AT rules' Gaussian draws of the full run), must give the remaining particles the same new
// velocities as the full run, and each group the change its particles had there (the sum of
// v' - v and of r (v' - v)^T), for SRD, MPC-AT and MPC-AT+a in 2D and 3D.
//
// Tolerance: the cell sums are fixed point (2^-41 a term), and a group enters them as a few
// sums instead of one term per particle; every velocity below is O(1-3) and a cell holds at most
// 12 particles, so both runs agree to ~1e-11; 1e-9 leaves room and is far below any error of
// the algebra (a term of one particle's velocity, O(1)).
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>
#include <vector>

namespace {

using namespace narrows;
using namespace narrows::mpcd;

enum class Rule { srd, at, at_a };

void collide(Rule r, Fluid &f, const CellGrid &g, CollisionScratch &s) {
  const std::uint64_t seed = 11, step = 5;
  if (r == Rule::srd)
    collide_srd(f, g, s, 130.0 * M_PI / 180.0, seed, step);
  else if (r == Rule::at)
    collide_at(f, g, s, 1.0, seed, step);
  else
    collide_at_a(f, g, s, 1.0, seed, step);
}

// Offset from the corner of the shifted cell, as the rules take it.
double in_cell(double x, double s) {
  const double t = x - s;
  return t - std::floor(t);
}

void check(Rule rule, int dim) {
  const Box box = make_periodic_box(dim, {4, 3, dim == 3 ? 3 : 1});
  std::mt19937_64 gen(42 + dim);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  // Random particles with a flow of its own in every cell (spin included, so that AT+a's
  // angular correction acts on the groups), ids scattered.
  Fluid all;
  all.dim = dim;
  const std::size_t n = box.num_cells() * 9;
  all.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    all.id[i] = 1000 + 7 * i;
    for (int k = 0; k < dim; ++k) {
      all.x[k][i] = u01(gen) * box.length[k];
      all.v[k][i] = 0.5 * std::sin(all.x[(k + 1) % dim][i]) + gauss(gen);
    }
  }
  CellGrid full(box);
  full.set_shift(grid_shift(3, 5, dim));
  bin_particles(all, full);
  CollisionScratch sa;
  Fluid after = all;
  collide(rule, after, full, sa);

  // The same particles, one in three taken into one of its cell's two groups (groups of one
  // particle too).
  Fluid rest;
  rest.dim = dim;
  std::vector<std::size_t> rest_of; // row in `all`
  // Two groups a cell (as two colloids cutting one cell): slot 2 c and 2 c + 1.
  std::vector<ParticleGroup> group(2 * full.size());
  std::vector<GroupChange> expected(2 * full.size());
  std::vector<bool> has(2 * full.size(), false);
  std::vector<std::size_t> slot_of; // per entry of part.groups
  for (std::size_t i = 0; i < n; ++i) {
    if (all.id[i] % 3 != 0) {
      rest.resize(rest.size() + 1);
      const std::size_t j = rest.size() - 1;
      rest.id[j] = all.id[i];
      for (int k = 0; k < dim; ++k) {
        rest.x[k][j] = all.x[k][i];
        rest.v[k][j] = all.v[k][i];
      }
      rest_of.push_back(i);
      continue;
    }
    const std::uint32_t cell = all.cell[i];
    const std::size_t c = 2 * cell + (all.id[i] % 2); // which of the cell's two groups
    ParticleGroup &q = group[c];
    has[c] = true;
    q.cell = cell;
    q.n += 1;
    double r[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < dim; ++k)
      r[k] = in_cell(all.x[k][i], full.shift[k]);
    for (int a = 0; a < dim; ++a) {
      q.r[a] += r[a];
      q.v[a] += all.v[a][i];
      // The AT rules' draw of this particle in the full run (SRD: none, zero).
      const double xi = rule == Rule::srd ? 0.0 : sa.noise[a][i];
      q.xi[a] += xi;
      for (int b = 0; b < dim; ++b) {
        q.rr[3 * a + b] += r[a] * r[b];
        q.rv[3 * a + b] += r[a] * all.v[b][i];
        q.rxi[3 * a + b] += r[a] * (rule == Rule::srd ? 0.0 : sa.noise[b][i]);
        expected[c].rv[3 * a + b] += r[a] * (after.v[b][i] - all.v[b][i]);
      }
      expected[c].v[a] += after.v[a][i] - all.v[a][i];
    }
  }
  CellGrid part(box);
  part.set_shift(full.shift);
  bin_particles(rest, part);
  for (std::size_t c = 0; c < group.size(); ++c) {
    if (!has[c])
      continue;
    part.groups.push_back(group[c]);
    slot_of.push_back(c);
    part.sums[c / 2].n += group[c].n; // as the coupling adds them
    for (int k = 0; k < dim; ++k)
      part.sums[c / 2].p[k] += fixed::from_double(group[c].v[k]);
  }
  ASSERT_GT(part.groups.size(), part.size()); // so some cells hold two groups
  CollisionScratch sb;
  collide(rule, rest, part, sb);

  double worst_particle = 0.0, worst_group = 0.0, largest = 0.0;
  for (std::size_t j = 0; j < rest.size(); ++j)
    for (int k = 0; k < dim; ++k)
      worst_particle = std::max(worst_particle, std::abs(rest.v[k][j] - after.v[k][rest_of[j]]));
  ASSERT_EQ(sb.group_change.size(), part.groups.size());
  for (std::size_t g = 0; g < part.groups.size(); ++g) {
    const GroupChange &got = sb.group_change[g], &want = expected[slot_of[g]];
    for (int a = 0; a < dim; ++a) {
      worst_group = std::max(worst_group, std::abs(got.v[a] - want.v[a]));
      largest = std::max(largest, std::abs(want.v[a]));
      for (int b = 0; b < dim; ++b)
        worst_group = std::max(worst_group, std::abs(got.rv[3 * a + b] - want.rv[3 * a + b]));
    }
  }
  std::printf("largest difference: particles %.3g, group sums %.3g (largest group change %.3g)\n",
              worst_particle, worst_group, largest);
  EXPECT_LT(worst_particle, 1e-9);
  EXPECT_LT(worst_group, 1e-9);
  EXPECT_GT(largest, 0.5); // the groups did change
}

} // namespace

TEST(ParticleGroups, SrdCollidesAGroupAsItsParticles2D) { check(Rule::srd, 2); }
TEST(ParticleGroups, SrdCollidesAGroupAsItsParticles3D) { check(Rule::srd, 3); }
TEST(ParticleGroups, AtCollidesAGroupAsItsParticles2D) { check(Rule::at, 2); }
TEST(ParticleGroups, AtCollidesAGroupAsItsParticles3D) { check(Rule::at, 3); }
TEST(ParticleGroups, AtaCollidesAGroupAsItsParticles2D) { check(Rule::at_a, 2); }
TEST(ParticleGroups, AtaCollidesAGroupAsItsParticles3D) { check(Rule::at_a, 3); }
