// Collision rules on many random cells built directly (0, 1, 2, 3, ... 50 particles): per-cell
// conservation laws, the SRD rotation itself, the AT velocity statistics, determinism and
// independence of particle order; and the random-solvent rules.
//
// Tolerances. Cell means come from fixed-point sums (core/fixed_point.hpp) that round each
// term by at most 2^-41, so a cell sum of n terms is off by at most n 2^-41 and a cell mean by
// 2^-41 per component. Every conservation error below is a few such sums times the size of
// what multiplies them (|u|, |v|, |omega|), plus double rounding of O(eps |v|) per particle.
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace narrows;
using namespace narrows::mpcd;

constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr double q = 0x1p-40; // fixed-point resolution; rounding of one term <= q/2

enum class Rule { srd, at, at_a };
const char *name(Rule r) { return r == Rule::srd ? "srd" : r == Rule::at ? "at" : "at+a"; }

Box make_box(int dim, std::array<int, 3> cells) { return make_periodic_box(dim, cells); }

struct Scene {
  Box box;
  Fluid f;
  CellGrid g;
  std::vector<std::uint32_t> n; // intended particles per cell
  std::vector<bool> collinear;  // 3D cells whose particles lie on one line
};

// Random cells: each cell c gets counts[...] particles at random offsets inside the shifted
// cell, velocities = a random cell flow + Gaussian at kT. Particles are stored in random
// order with scattered 64-bit ids. In 3D, half the 3-particle cells are collinear.
Scene make_scene(int dim, std::array<int, 3> cells, std::uint64_t seed,
                 const std::vector<std::uint32_t> &counts, double kT, bool random_count = true) {
  Scene s;
  s.box = make_box(dim, cells);
  s.g = CellGrid(s.box);
  s.g.shift = grid_shift(seed, 17, dim);
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> uoff(1e-6, 1.0 - 1e-6), uflow(-1.0, 1.0);
  std::normal_distribution<double> gauss(0.0, std::sqrt(kT));
  const std::size_t nc = s.box.num_cells();
  s.n.resize(nc);
  s.collinear.assign(nc, false);
  struct P {
    double x[3], v[3];
  };
  std::vector<P> parts;
  const int nx = s.g.cells[0], ny = s.g.cells[1];
  for (std::size_t c = 0; c < nc; ++c) {
    const std::uint32_t cnt =
        random_count ? counts[gen() % counts.size()] : counts[c % counts.size()];
    s.n[c] = cnt;
    const int cc[3] = {static_cast<int>(c % nx), static_cast<int>((c / nx) % ny),
                       static_cast<int>(c / (static_cast<std::size_t>(nx) * ny))};
    double flow[3];
    for (int k = 0; k < dim; ++k)
      flow[k] = uflow(gen);
    const bool line = dim == 3 && cnt == 3 && (gen() & 1u);
    s.collinear[c] = line;
    double p0[3], d[3];
    if (line) {
      double norm = 0;
      for (int k = 0; k < 3; ++k) {
        p0[k] = 0.2 + 0.6 * uoff(gen);
        d[k] = gauss(gen);
        norm += d[k] * d[k];
      }
      for (int k = 0; k < 3; ++k)
        d[k] /= std::sqrt(norm);
    }
    for (std::uint32_t j = 0; j < cnt; ++j) {
      P p{};
      const double t = 0.3 * (uoff(gen) - 0.5);
      for (int k = 0; k < dim; ++k) {
        const double off = line ? p0[k] + t * d[k] : uoff(gen);
        const double L = s.box.length[k];
        double x = cc[k] + s.g.shift[k] + off;
        if (x >= L)
          x -= L;
        if (x < 0)
          x += L;
        p.x[k] = x;
        p.v[k] = flow[k] + gauss(gen);
      }
      parts.push_back(p);
    }
  }
  std::shuffle(parts.begin(), parts.end(), gen);
  const std::size_t np = parts.size();
  std::vector<std::uint64_t> ids(np);
  std::iota(ids.begin(), ids.end(), 0);
  std::shuffle(ids.begin(), ids.end(), gen);
  s.f.dim = dim;
  s.f.resize(np);
  for (std::size_t i = 0; i < np; ++i) {
    s.f.id[i] = ids[i] * 7919 + (ids[i] % 3) * 0x100000000ull; // scattered, some above 2^32
    for (int k = 0; k < dim; ++k) {
      s.f.x[k][i] = parts[i].x[k];
      s.f.v[k][i] = parts[i].v[k];
    }
  }
  bin_particles(s.f, s.g);
  return s;
}

void collide(Rule r, Fluid &f, const CellGrid &g, CollisionScratch &sc, double angle, double kT,
             std::uint64_t seed, std::uint64_t step) {
  switch (r) {
  case Rule::srd:
    collide_srd(f, g, sc, angle, seed, step);
    break;
  case Rule::at:
    collide_at(f, g, sc, kT, seed, step);
    break;
  case Rule::at_a:
    collide_at_a(f, g, sc, kT, seed, step);
    break;
  }
}

// Offset of a particle from the corner of its shifted cell, as in collision_at.cpp.
double in_cell(double x, double shift) {
  const double t = x - shift + 1.0;
  return t - std::floor(t);
}

using LD = long double;

struct CellStat {
  std::uint32_t n = 0;
  LD P[3] = {0, 0, 0}, E = 0, L[3] = {0, 0, 0}; // L about the cell corner (2D: L[2])
  double vmax = 0;
};

std::vector<CellStat> cell_stats(const Fluid &f, const CellGrid &g) {
  std::vector<CellStat> st(g.size());
  const int D = f.dim;
  for (std::size_t i = 0; i < f.size(); ++i) {
    CellStat &c = st[f.cell[i]];
    c.n += 1;
    LD r[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      r[k] = in_cell(f.x[k][i], g.shift[k]);
      v[k] = f.v[k][i];
      c.P[k] += v[k];
      c.E += 0.5L * v[k] * v[k];
      c.vmax = std::max(c.vmax, std::abs(f.v[k][i]));
    }
    c.L[0] += r[1] * v[2] - r[2] * v[1];
    c.L[1] += r[2] * v[0] - r[0] * v[2];
    c.L[2] += r[0] * v[1] - r[1] * v[0];
  }
  return st;
}

// Reference angular velocity of the AT+a correction, in long double from the exact data:
// omega = I^+ sum (r - rbar) x (v - xi), with the pseudo-inverse for singular I. Used only to
// size the tolerance (the rigid-rotation term multiplies the rounding of rc by |omega|).
std::vector<double> omega_ref(const Fluid &before, const CollisionScratch &sc, const CellGrid &g) {
  const int D = before.dim;
  const std::size_t nc = g.size();
  std::vector<std::vector<std::size_t>> members(nc);
  for (std::size_t i = 0; i < before.size(); ++i)
    members[before.cell[i]].push_back(i);
  std::vector<double> om(nc, 0.0);
  for (std::size_t c = 0; c < nc; ++c) {
    const auto &m = members[c];
    if (m.size() < 2)
      continue;
    LD rb[3] = {0, 0, 0};
    for (auto i : m)
      for (int k = 0; k < D; ++k)
        rb[k] += in_cell(before.x[k][i], g.shift[k]);
    for (int k = 0; k < D; ++k)
      rb[k] /= m.size();
    Eigen::Matrix<LD, 3, 3> I = Eigen::Matrix<LD, 3, 3>::Zero();
    Eigen::Matrix<LD, 3, 1> dL = Eigen::Matrix<LD, 3, 1>::Zero();
    for (auto i : m) {
      Eigen::Matrix<LD, 3, 1> r = Eigen::Matrix<LD, 3, 1>::Zero(), w = r;
      for (int k = 0; k < D; ++k) {
        r[k] = in_cell(before.x[k][i], g.shift[k]) - rb[k];
        w[k] = static_cast<LD>(before.v[k][i]) - sc.noise[k][i];
      }
      dL += r.cross(w);
      I += r.squaredNorm() * Eigen::Matrix<LD, 3, 3>::Identity() - r * r.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<LD, 3, 3>> eig(I);
    const auto lam = eig.eigenvalues();
    const LD cut = 1e-9L * lam.cwiseAbs().maxCoeff();
    Eigen::Matrix<LD, 3, 1> inv;
    for (int k = 0; k < 3; ++k)
      inv[k] = std::abs(lam[k]) > cut ? 1.0L / lam[k] : 0.0L;
    if (D == 2) { // only the z component exists: I_zz = sum |r|^2
      om[c] = static_cast<double>(std::abs(dL[2] / I(2, 2)));
    } else {
      const Eigen::Matrix<LD, 3, 1> w =
          eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose() * dL;
      om[c] = static_cast<double>(w.norm());
    }
  }
  return om;
}

// Worst error/tolerance ratio per (quantity, kind of cell), with a description of that cell.
struct Worst {
  double ratio = 0;
  std::string what;
};
using Report = std::map<std::string, Worst>;

std::string kind(std::uint32_t n, bool collinear) {
  if (n >= 4)
    return "n>=4";
  return "n=" + std::to_string(n) + (collinear ? " collinear" : "");
}

void note(Report &rep, const std::string &key, double err, double tol, const std::string &what) {
  Worst &w = rep[key];
  if (!(err <= w.ratio * tol)) { // also catches NaN
    w.ratio = err / tol;
    std::ostringstream os;
    os << what << ": error " << err << " (" << err / q << " q), tolerance " << tol << " ("
       << tol / q << " q)";
    w.what = os.str();
  }
}

// Runs one rule on one scene and records the per-cell conservation errors.
void check_conservation(Rule rule, int dim, std::uint64_t seed, Report &rep,
                        std::map<std::string, std::size_t> &cells_of_kind) {
  const std::vector<std::uint32_t> pattern = {0, 1, 2, 3, 3, 4, 7, 12, 50};
  const std::array<int, 3> cells =
      dim == 2 ? std::array<int, 3>{50, 40, 1} : std::array<int, 3>{14, 13, 11};
  const double kT = 1.3, angle = 130.0 * std::numbers::pi / 180.0;
  Scene s = make_scene(dim, cells, seed, pattern, kT);
  for (std::size_t c = 0; c < s.g.size(); ++c)
    ASSERT_EQ(s.g.sums[c].n, s.n[c]) << "scene construction: cell " << c;
  const Fluid before = s.f;
  CollisionScratch sc;
  const std::uint64_t step = 1000 + seed;
  collide(rule, s.f, s.g, sc, angle, kT, seed, step);
  const auto b = cell_stats(before, s.g), a = cell_stats(s.f, s.g);
  std::vector<double> om(s.g.size(), 0.0);
  if (rule == Rule::at_a)
    om = omega_ref(before, sc, s.g);
  for (std::size_t c = 0; c < s.g.size(); ++c) {
    const double n = b[c].n;
    const std::string k_ = kind(b[c].n, s.collinear[c]);
    cells_of_kind[k_] += 1;
    if (b[c].n == 0)
      continue;
    std::ostringstream os;
    os << name(rule) << " " << dim << "D seed " << seed << " cell " << c << " (" << k_
       << ", |omega_ref| " << om[c] << ")";
    const std::string where = os.str();
    const double vmax = std::max(b[c].vmax, a[c].vmax);
    // Momentum: srd n (R - 1) (vbar - u): |.| <= 2 n |vbar - u| <= n q sqrt(D); at(+a): the
    // fixed-point sums of v and xi, n q; at+a also |omega| |sum (r - rc)| <= |omega| n q.
    // Bound: 2 n q (1 + |omega|) plus 16 eps per particle of the velocities involved.
    const double tolP = 2 * n * q * (1 + om[c]) + 16 * n * eps * (vmax + om[c]);
    for (int k = 0; k < dim; ++k)
      note(rep, "momentum " + k_, std::abs(static_cast<double>(a[c].P[k] - b[c].P[k])), tolP,
           where + " axis " + std::to_string(k));
    if (rule == Rule::srd) {
      // Energy: u . (R - 1) sum w with |sum w| <= n q sqrt(D)/2: <= 2 |u| n q; |u| <= vmax.
      // Rounding: 16 eps per particle of vmax^2.
      const double tolE = 2 * n * q * vmax + 16 * n * eps * vmax * vmax;
      note(rep, "energy " + k_, std::abs(static_cast<double>(a[c].E - b[c].E)), tolE, where);
    }
    if (rule == Rule::at_a) {
      // Angular momentum about the corner: the fixed-point sums of r x v, r x xi, r, r r^T
      // each err by <= n q/2, multiplied by |v|, |xi|, |omega| and |r| <= sqrt(3): bounded by
      // 8 n q (1 + vmax + |omega|); double rounding 64 eps per particle of (vmax + |omega|).
      const double tolL = 8 * n * q * (1 + vmax + om[c]) + 64 * n * eps * (vmax + om[c]);
      for (int k = (dim == 2 ? 2 : 0); k < 3; ++k)
        note(rep, "angular momentum " + k_, std::abs(static_cast<double>(a[c].L[k] - b[c].L[k])),
             tolL, where + " component " + std::to_string(k));
    }
  }
  // Positions, ids and cells are untouched.
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(s.f.x[k], before.x[k]);
  EXPECT_EQ(s.f.id, before.id);
  EXPECT_EQ(s.f.cell, before.cell);
}

void run_conservation(Rule rule, int dim) {
  Report rep;
  std::map<std::string, std::size_t> cells_of_kind;
  for (std::uint64_t seed : {1ull, 2ull, 3ull, 4ull, 5ull})
    check_conservation(rule, dim, seed, rep, cells_of_kind);
  // Known failure (at+a, 3D, cells with 1 or 2 particles or collinear ones): LIBRARY BUG in
  // src/engines/mpcd/kernels/collision_at.cpp, at_a_kernel<3>: (1) the pseudo-inverse cut 1e-10
  // max|lambda| has no absolute floor, so the O(q) rounding noise of I along its null direction is
  // inverted (spurious |omega| up to ~1e5); (2) computeDirect loses about half the digits for the
  // double eigenvalue of I (I w - dL ~ 1e-8 |dL|). compute() plus an absolute floor passes.
  const char *hint =
      rule == Rule::at_a && dim == 3
          ? " [LIBRARY BUG src/engines/mpcd/kernels/collision_at.cpp at_a_kernel<3>: relative-only "
            "pseudo-inverse cut inverts fixed-point noise; computeDirect inaccurate "
            "for the double eigenvalue of I]"
          : "";
  for (const auto &[key, w] : rep)
    EXPECT_LE(w.ratio, 1.0) << key << " not conserved; worst: " << w.what << hint;
  // The scenes did contain the small cells the brief is about.
  for (const char *k : {"n=0", "n=1", "n=2", "n=3", "n>=4"})
    EXPECT_GT(cells_of_kind[k], 100u) << "cells of kind " << k;
  if (dim == 3) {
    EXPECT_GT(cells_of_kind["n=3 collinear"], 100u);
  }
}

TEST(CollisionSrd, ConservesMomentumEnergy2D) { run_conservation(Rule::srd, 2); }
TEST(CollisionSrd, ConservesMomentumEnergy3D) { run_conservation(Rule::srd, 3); }
TEST(CollisionAt, ConservesMomentum2D) { run_conservation(Rule::at, 2); }
TEST(CollisionAt, ConservesMomentum3D) { run_conservation(Rule::at, 3); }
TEST(CollisionAtA, ConservesMomentumAngularMomentum2D) { run_conservation(Rule::at_a, 2); }
TEST(CollisionAtA, ConservesMomentumAngularMomentum3D) { run_conservation(Rule::at_a, 3); }

// SRD in 2D rotates every relative velocity w = v - u of a cell by the same +-alpha.
TEST(CollisionSrd, Rotates2DRelativeVelocitiesByAlpha) {
  const double alpha = 130.0 * std::numbers::pi / 180.0;
  std::size_t plus = 0, minus = 0;
  for (std::uint64_t seed : {11ull, 12ull, 13ull}) {
    Scene s = make_scene(2, {50, 40, 1}, seed, {1, 2, 3, 5, 10, 50}, 1.0);
    const Fluid before = s.f;
    CollisionScratch sc;
    collide_srd(s.f, s.g, sc, alpha, seed, 3);
    std::vector<int> sign(s.g.size(), 0);
    for (std::size_t i = 0; i < s.f.size(); ++i) {
      const std::uint32_t c = s.f.cell[i];
      const double n = s.g.sums[c].n;
      const double u[2] = {fixed::to_double(s.g.sums[c].p[0]) / n,
                           fixed::to_double(s.g.sums[c].p[1]) / n};
      const double w[2] = {before.v[0][i] - u[0], before.v[1][i] - u[1]};
      const double w2[2] = {s.f.v[0][i] - u[0], s.f.v[1][i] - u[1]};
      const double nw = std::hypot(w[0], w[1]), nw2 = std::hypot(w2[0], w2[1]);
      // v' = u + R w and w' = v' - u: a few roundings of size eps (|u| + |w|).
      const double tol = 16 * eps * (std::hypot(u[0], u[1]) + nw);
      ASSERT_NEAR(nw2, nw, tol) << "|w| changed, particle " << i << " cell " << c;
      if (s.g.sums[c].n < 2) { // nothing to rotate: the identity
        ASSERT_NEAR(s.f.v[0][i], before.v[0][i], tol);
        ASSERT_NEAR(s.f.v[1][i], before.v[1][i], tol);
        continue;
      }
      if (nw < 1e-6)
        continue; // direction undefined
      const double ang = std::atan2(w[0] * w2[1] - w[1] * w2[0], w[0] * w2[0] + w[1] * w2[1]);
      const int sg = ang > 0 ? 1 : -1;
      // Angle error: the tolerance on w' over |w|, plus atan2 rounding.
      ASSERT_NEAR(std::abs(ang), alpha, tol / nw + 8 * eps)
          << "rotation angle, particle " << i << " cell " << c;
      if (sign[c] == 0)
        sign[c] = sg;
      ASSERT_EQ(sign[c], sg) << "particles of cell " << c << " rotated in different senses";
    }
    for (int sg : sign) {
      plus += sg > 0;
      minus += sg < 0;
    }
  }
  // The sense is a fair coin per cell: 5 sigma of a binomial with p = 1/2.
  const double m = plus + minus;
  EXPECT_LT(std::abs(plus / m - 0.5), 5 * 0.5 / std::sqrt(m)) << plus << " + vs " << minus << " -";
}

// SRD in 3D: the relative velocities of a cell undergo one rotation by alpha: their Gram
// matrix is preserved, and each turns by at most alpha (exactly alpha when normal to the axis).
TEST(CollisionSrd, Rotates3DRelativeVelocitiesRigidly) {
  const double alpha = 100.0 * std::numbers::pi / 180.0;
  for (std::uint64_t seed : {21ull, 22ull}) {
    Scene s = make_scene(3, {14, 13, 11}, seed, {1, 2, 3, 6, 20}, 1.0);
    const Fluid before = s.f;
    CollisionScratch sc;
    collide_srd(s.f, s.g, sc, alpha, seed, 4);
    std::vector<std::vector<std::size_t>> members(s.g.size());
    for (std::size_t i = 0; i < s.f.size(); ++i)
      members[s.f.cell[i]].push_back(i);
    std::size_t near_alpha = 0, multi = 0;
    for (std::size_t c = 0; c < s.g.size(); ++c) {
      const auto &m = members[c];
      const double n = m.size();
      if (m.size() < 2)
        continue;
      ++multi;
      double u[3];
      for (int k = 0; k < 3; ++k)
        u[k] = fixed::to_double(s.g.sums[c].p[k]) / n;
      std::vector<std::array<double, 3>> w(m.size()), w2(m.size());
      double umag = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      double best = 0;
      for (std::size_t j = 0; j < m.size(); ++j)
        for (int k = 0; k < 3; ++k) {
          w[j][k] = before.v[k][m[j]] - u[k];
          w2[j][k] = s.f.v[k][m[j]] - u[k];
        }
      auto dot = [](const std::array<double, 3> &a, const std::array<double, 3> &b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      };
      for (std::size_t j = 0; j < m.size(); ++j) {
        const double nj = std::sqrt(dot(w[j], w[j]));
        for (std::size_t l = j; l < m.size(); ++l) {
          const double nl = std::sqrt(dot(w[l], w[l]));
          // R orthogonal to ~4 eps; w' carries rounding 16 eps (|u| + |w|).
          const double tol = 32 * eps * (umag + nj) * (umag + nl);
          ASSERT_NEAR(dot(w2[j], w2[l]), dot(w[j], w[l]), tol)
              << "Gram matrix of cell " << c << " entry " << j << "," << l;
        }
        if (nj > 1e-6) {
          const double cosang = dot(w[j], w2[j]) / (nj * nj);
          ASSERT_GE(cosang, std::cos(alpha) - 32 * eps * (umag + nj) / nj)
              << "relative velocity turned by more than alpha, cell " << c;
          best = std::max(best, std::acos(std::clamp(cosang, -1.0, 1.0)));
        }
      }
      near_alpha += best > 0.5 * alpha;
    }
    // Random axes: most multi-particle cells have a relative velocity turned by > alpha/2.
    EXPECT_GT(near_alpha, multi / 2);
  }
}

// AT and AT+a: after the collision, v - (cell mean) has variance kT (n - 1)/n per component.
void check_relative_variance(Rule rule, int dim) {
  const double kT = 1.7;
  const std::vector<std::uint32_t> ns = {2, 3, 5, 10};
  std::map<std::uint32_t, std::vector<std::array<double, 3>>> ss; // per cell sum of squares
  for (std::uint64_t seed : {31ull, 32ull, 33ull, 34ull}) {
    const std::array<int, 3> cells =
        dim == 2 ? std::array<int, 3>{50, 40, 1} : std::array<int, 3>{14, 13, 11};
    Scene s = make_scene(dim, cells, seed, ns, kT, false);
    CollisionScratch sc;
    collide(rule, s.f, s.g, sc, 0.0, kT, seed, 9);
    const auto st = cell_stats(s.f, s.g);
    std::vector<std::array<double, 3>> sq(s.g.size(), {0, 0, 0});
    for (std::size_t i = 0; i < s.f.size(); ++i) {
      const std::uint32_t c = s.f.cell[i];
      for (int k = 0; k < dim; ++k) {
        const double d = s.f.v[k][i] - static_cast<double>(st[c].P[k] / st[c].n);
        sq[c][k] += d * d;
      }
    }
    for (std::size_t c = 0; c < s.g.size(); ++c)
      ss[st[c].n].push_back(sq[c]);
  }
  for (auto n : ns) {
    const auto &v = ss[n];
    ASSERT_GT(v.size(), 300u);
    const double M = v.size();
    for (int k = 0; k < dim; ++k) {
      double m1 = 0, m2 = 0;
      for (const auto &x : v) {
        m1 += x[k];
        m2 += x[k] * x[k];
      }
      m1 /= M;
      m2 /= M;
      const double est = m1 / n, want = kT * (n - 1.0) / n;
      // AT: the per-cell sum of squares is kT chi^2(n - 1), sigma of the estimate
      // kT sqrt(2 (n - 1) / M) / n. AT+a mixes the components through the rotation, so its
      // sigma is the empirical one, sqrt(Var(ss) / M) / n.
      const double sigma = rule == Rule::at ? kT * std::sqrt(2.0 * (n - 1) / M) / n
                                            : std::sqrt((m2 - m1 * m1) / M) / n;
      EXPECT_NEAR(est, want, 5 * sigma)
          << name(rule) << " " << dim << "D, n = " << n << ", axis " << k << ", cells " << M;
    }
  }
}

TEST(CollisionAt, RelativeVarianceIsKTnm1overn2D) { check_relative_variance(Rule::at, 2); }
TEST(CollisionAt, RelativeVarianceIsKTnm1overn3D) { check_relative_variance(Rule::at, 3); }
TEST(CollisionAtA, RelativeVarianceIsKTnm1overn2D) { check_relative_variance(Rule::at_a, 2); }
TEST(CollisionAtA, RelativeVarianceIsKTnm1overn3D) { check_relative_variance(Rule::at_a, 3); }

// A single-particle cell keeps its velocity: AT gives xi + (v - xi), exact up to the two
// fixed-point roundings (q) and eps |xi|.
TEST(CollisionAt, SingleParticleCellsKeepVelocity) {
  for (int dim : {2, 3}) {
    Scene s =
        make_scene(dim, dim == 2 ? std::array<int, 3>{30, 30, 1} : std::array<int, 3>{10, 10, 10},
                   41, {1}, 1.0);
    Fluid f = s.f;
    CollisionScratch sc;
    collide_at(f, s.g, sc, 1.0, 41, 2);
    for (std::size_t i = 0; i < f.size(); ++i)
      for (int k = 0; k < dim; ++k)
        ASSERT_NEAR(f.v[k][i], s.f.v[k][i],
                    q + 8 * eps * (std::abs(sc.noise[k][i]) + std::abs(s.f.v[k][i])))
            << dim << "D particle " << i << " axis " << k;
  }
}

// AT+a on a single-particle cell: the moment of inertia is zero, so the rotation must vanish
// and v' = v as for AT. The fixed-point sums leave noise of order q in I and dL; in 2D the
// cut I > 1e-12 (~ q) bounds the spurious |omega| by ~ |dL|/1e-12 ~ (1 + |v| + |xi|), and it
// multiplies |r - rc| <= q: tolerance 2 q (1 + |v| + |xi|).
TEST(CollisionAtA, SingleParticleCellsKeepVelocity) {
  for (int dim : {2, 3}) {
    Scene s =
        make_scene(dim, dim == 2 ? std::array<int, 3>{30, 30, 1} : std::array<int, 3>{10, 10, 10},
                   41, {1}, 1.0);
    Fluid f = s.f;
    CollisionScratch sc;
    collide_at_a(f, s.g, sc, 1.0, 41, 2);
    double worst = 0;
    std::size_t worst_i = 0;
    for (std::size_t i = 0; i < f.size(); ++i)
      for (int k = 0; k < dim; ++k) {
        const double tol = 2 * q * (1 + std::abs(sc.noise[k][i]) + std::abs(s.f.v[k][i]));
        const double r = std::abs(f.v[k][i] - s.f.v[k][i]) / tol;
        if (!(r <= worst)) {
          worst = r;
          worst_i = i;
        }
      }
    EXPECT_LE(worst, 1.0) << (dim == 3 ? "LIBRARY BUG (src/engines/mpcd/kernels/collision_at.cpp "
                                         "at_a_kernel<3>: the pseudo-inverse cut is relative "
                                         "only, so the pure rounding noise of I is inverted): "
                                       : "")
                          << dim << "D: single-particle cell velocity changed by " << worst
                          << " x tolerance (particle " << worst_i << ", v " << s.f.v[0][worst_i]
                          << " -> " << f.v[0][worst_i] << ")";
  }
}

bool bitwise_equal(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Same inputs give bitwise-identical outputs, also with a scratch dirtied by other calls; and
// reversing the particle arrays gives bitwise-identical per-particle results.
void check_determinism(Rule rule, int dim) {
  const std::array<int, 3> cells =
      dim == 2 ? std::array<int, 3>{30, 20, 1} : std::array<int, 3>{8, 7, 6};
  const double kT = 0.9, angle = 2.0;
  Scene s = make_scene(dim, cells, 51 + dim, {0, 1, 2, 3, 4, 9, 50}, kT);
  Fluid a = s.f, b = s.f;
  CollisionScratch sa, sb;
  // Dirty sb with a different rule, size and step first.
  {
    Scene other = make_scene(dim, {5, 5, dim == 3 ? 5 : 1}, 7, {3, 8}, 2.0);
    collide(Rule::at_a, other.f, other.g, sb, angle, 2.0, 1, 1);
    collide(Rule::srd, other.f, other.g, sb, angle, 2.0, 1, 1);
  }
  collide(rule, a, s.g, sa, angle, kT, 99, 5);
  collide(rule, b, s.g, sb, angle, kT, 99, 5);
  for (int k = 0; k < dim; ++k)
    for (std::size_t i = 0; i < a.size(); ++i)
      ASSERT_TRUE(bitwise_equal(a.v[k][i], b.v[k][i]))
          << name(rule) << " " << dim << "D rerun differs, particle " << i << " axis " << k;

  // Reversed arrays, binned afresh into the same shifted grid.
  Fluid r = s.f;
  for (int k = 0; k < dim; ++k) {
    std::reverse(r.x[k].begin(), r.x[k].end());
    std::reverse(r.v[k].begin(), r.v[k].end());
  }
  std::reverse(r.id.begin(), r.id.end());
  CellGrid gr = s.g;
  bin_particles(r, gr);
  for (std::size_t c = 0; c < gr.size(); ++c) {
    ASSERT_EQ(gr.sums[c].n, s.g.sums[c].n);
    ASSERT_EQ(gr.sums[c].p, s.g.sums[c].p) << "fixed-point sums depend on order, cell " << c;
  }
  CollisionScratch sr;
  collide(rule, r, gr, sr, angle, kT, 99, 5);
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(r.id[n - 1 - i], a.id[i]);
    for (int k = 0; k < dim; ++k)
      ASSERT_TRUE(bitwise_equal(a.v[k][i], r.v[k][n - 1 - i]))
          << name(rule) << " " << dim << "D order dependence: id " << a.id[i] << " axis " << k
          << ": " << a.v[k][i] << " vs " << r.v[k][n - 1 - i];
  }
  // A different step or seed does change the result (the rule is not a no-op).
  Fluid c = s.f;
  CollisionScratch scc;
  collide(rule, c, s.g, scc, angle, kT, 99, 6);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < n; ++i)
    changed += !bitwise_equal(a.v[0][i], c.v[0][i]);
  // (2D SRD draws only a sign per cell, so about half the cells repeat their rotation.)
  EXPECT_GT(changed, n / 4) << name(rule) << " ignores the step";
}

TEST(CollisionSrd, DeterministicAndOrderIndependent2D) { check_determinism(Rule::srd, 2); }
TEST(CollisionSrd, DeterministicAndOrderIndependent3D) { check_determinism(Rule::srd, 3); }
TEST(CollisionAt, DeterministicAndOrderIndependent2D) { check_determinism(Rule::at, 2); }
TEST(CollisionAt, DeterministicAndOrderIndependent3D) { check_determinism(Rule::at, 3); }
TEST(CollisionAtA, DeterministicAndOrderIndependent2D) { check_determinism(Rule::at_a, 2); }
TEST(CollisionAtA, DeterministicAndOrderIndependent3D) { check_determinism(Rule::at_a, 3); }

Fluid plain_fluid(int dim, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> g(0.3, 1.1);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  Fluid f;
  f.dim = dim;
  f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = 5 * i + 3;
    for (int k = 0; k < dim; ++k) {
      f.x[k][i] = u(gen);
      f.v[k][i] = g(gen);
    }
  }
  return f;
}

std::vector<std::array<double, 3>> velocity_tuples(const Fluid &f) {
  std::vector<std::array<double, 3>> t(f.size(), {0, 0, 0});
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < f.dim; ++k)
      t[i][k] = f.v[k][i];
  return t;
}

TEST(CollisionRandom, PermuteKeepsVelocityMultiset) {
  for (int dim : {2, 3}) {
    Fluid f = plain_fluid(dim, 10000, 61);
    const Fluid before = f;
    CollisionScratch sc;
    permute_velocities(f, sc, 61, 8);
    auto t0 = velocity_tuples(before), t1 = velocity_tuples(f);
    std::size_t moved = 0;
    for (std::size_t i = 0; i < t0.size(); ++i)
      moved += t0[i] != t1[i];
    EXPECT_GT(moved, f.size() * 99 / 100) << "permutation leaves too many velocities in place";
    std::sort(t0.begin(), t0.end());
    std::sort(t1.begin(), t1.end());
    ASSERT_EQ(t0, t1) << "the multiset of velocity tuples changed (" << dim << "D)";
    // Totals summed in the same (sorted) order are then exactly equal.
    double p0[3] = {0, 0, 0}, p1[3] = {0, 0, 0}, e0 = 0, e1 = 0;
    for (std::size_t i = 0; i < t0.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        p0[k] += t0[i][k];
        p1[k] += t1[i][k];
        e0 += t0[i][k] * t0[i][k];
        e1 += t1[i][k] * t1[i][k];
      }
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(p0[k], p1[k]);
    EXPECT_EQ(e0, e1);
    for (int k = 0; k < dim; ++k)
      EXPECT_EQ(f.x[k], before.x[k]);
    EXPECT_EQ(f.id, before.id);
    // Deterministic.
    Fluid g = before;
    permute_velocities(g, sc, 61, 8);
    for (int k = 0; k < dim; ++k)
      EXPECT_EQ(g.v[k], f.v[k]);
  }
}

TEST(CollisionRandom, PermutationIsUniform) {
  // 4 particles: all 24 permutations equally likely over 24000 steps. Pearson chi^2 with 23
  // degrees of freedom: mean 23, sigma sqrt(46) = 6.8; fail beyond 5 sigma (57).
  const int steps = 24000;
  std::map<std::array<double, 4>, int> seen;
  for (int st = 0; st < steps; ++st) {
    Fluid f;
    f.dim = 2;
    f.resize(4);
    for (int i = 0; i < 4; ++i) {
      f.id[i] = i;
      f.v[0][i] = i;
      f.v[1][i] = -i;
    }
    CollisionScratch sc;
    permute_velocities(f, sc, 77, st);
    seen[{f.v[0][0], f.v[0][1], f.v[0][2], f.v[0][3]}] += 1;
  }
  ASSERT_EQ(seen.size(), 24u) << "not every permutation occurs";
  const double e = steps / 24.0;
  double chi2 = 0;
  for (const auto &[perm, cnt] : seen)
    chi2 += (cnt - e) * (cnt - e) / e;
  EXPECT_LT(chi2, 23 + 5 * std::sqrt(46.0));
}

TEST(CollisionRandom, MaxwellKeyedByParticleId) {
  for (int dim : {2, 3}) {
    const double kT = 2.25;
    Fluid f = plain_fluid(dim, 40000, 71);
    Fluid r = f; // same particles, shuffled order
    std::mt19937_64 gen(5);
    std::vector<std::size_t> perm(f.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), gen);
    for (std::size_t i = 0; i < f.size(); ++i) {
      r.id[i] = f.id[perm[i]];
      for (int k = 0; k < dim; ++k) {
        r.x[k][i] = f.x[k][perm[i]];
        r.v[k][i] = f.v[k][perm[i]];
      }
    }
    const Fluid before = f;
    draw_maxwell_velocities(f, kT, 71, 12);
    draw_maxwell_velocities(r, kT, 71, 12);
    for (std::size_t i = 0; i < f.size(); ++i)
      for (int k = 0; k < dim; ++k)
        ASSERT_TRUE(bitwise_equal(r.v[k][i], f.v[k][perm[i]]))
            << "velocity of id " << r.id[i] << " depends on its position in the array";
    for (int k = 0; k < dim; ++k)
      EXPECT_EQ(f.x[k], before.x[k]);
    // Maxwell-Boltzmann at kT: mean 0 (sigma sqrt(kT/N)), variance kT (sigma kT sqrt(2/N)).
    const double N = f.size();
    for (int k = 0; k < dim; ++k) {
      double m = 0, v2 = 0;
      for (double x : f.v[k]) {
        m += x;
        v2 += x * x;
      }
      m /= N;
      v2 = v2 / N - m * m;
      EXPECT_LT(std::abs(m), 5 * std::sqrt(kT / N)) << dim << "D axis " << k;
      EXPECT_LT(std::abs(v2 - kT), 5 * kT * std::sqrt(2.0 / N)) << dim << "D axis " << k;
    }
    // Another step draws other velocities.
    Fluid g = before;
    draw_maxwell_velocities(g, kT, 71, 13);
    std::size_t same = 0;
    for (std::size_t i = 0; i < g.size(); ++i)
      same += g.v[0][i] == f.v[0][i];
    EXPECT_EQ(same, 0u);
  }
}

} // namespace

// The largest |v|^2 the MPC-AT+a collision reports on its way (the next step's fluid reach of
// no-slip colloids on more than one rank, instead of a pass over the fluid) is the largest |v|^2
// of the velocities it left, to a rounding either way (bound 1e-12 relative, the margin the
// reach adds). Shown to fail by halving each particle's |v|^2 in the running maximum.
TEST(CollisionAtA, ReportsTheLargestSpeedItLeaves) {
  for (int dim : {2, 3}) {
    Scene s =
        make_scene(dim, dim == 2 ? std::array<int, 3>{30, 30, 1} : std::array<int, 3>{10, 10, 10},
                   43, {3, 7, 12}, 1.0);
    Fluid f = s.f;
    CollisionScratch sc;
    collide_at_a(f, s.g, sc, 1.0, 43, 5);
    double most = 0.0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      double v2 = 0.0;
      for (int k = 0; k < dim; ++k)
        v2 += f.v[k][i] * f.v[k][i];
      most = std::max(most, v2);
    }
    EXPECT_GT(most, 0.0);
    EXPECT_NEAR(sc.v2_max, most, 1e-12 * most) << dim << "D";
  }
}
