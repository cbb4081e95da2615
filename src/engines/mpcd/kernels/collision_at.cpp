// MPC-AT and MPC-AT+a (Kanehl (thesis) eq 4.5-4.11; Noguchi et al. (2007)).
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/core/rng_batch.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace narrows::mpcd {

namespace {

using fixed::from_double;
using fixed::to_double;

// The per-cell records of these kernels are read and summed into in particle order, which
// between sorts jumps around the cell array: fetching the record of the particle `ahead`
// places later hides the memory latency that otherwise bounds the loops.
constexpr std::size_t ahead = 64;
template <int D, std::size_t stride, class T>
inline void prefetch_record(const std::vector<T> &records, const std::uint32_t *cell, std::size_t i,
                            std::size_t n) {
  if (i + ahead >= n)
    return;
  // Every cache line the record can touch, a fixed number (a loop over those it does touch
  // missed its branch at random: MPC-AT+a 3D 10-18 % faster in the cache without it): a record
  // of 72 or 120 bytes at any offset can span three lines. In the plane only for the first
  // particle of a run in one cell (16-19 % faster in and beyond the cache); in space the same
  // test halved the speed (measured, cause not found), so there every particle fetches.
  constexpr std::size_t lines = (stride * sizeof(T) + 62) / 64 + 1;
  if constexpr (D == 2)
    if (cell[i + ahead] == cell[i + ahead - 1])
      return;
  const auto begin =
      reinterpret_cast<std::uintptr_t>(&records[cell[i + ahead] * stride]) & ~std::uintptr_t(63);
  for (std::size_t l = 0; l < lines; ++l)
    __builtin_prefetch(reinterpret_cast<const void *>(begin + 64 * l), 1);
}

// Gaussian velocities xi_i at kT for every particle (keyed by particle id), drawn a batch of
// ids at a time (core/rng_batch.hpp); after each batch, add(i) runs for its particles in
// order, to sum what the rule needs per cell while they are in cache. The last batch is padded
// with id 0 so that every id takes the same vector path (its deviates do not depend on where
// it sits in the array, hence not on the number of ranks).
template <int D, class Add>
void draw_noise(Fluid &f, CollisionScratch &s, double kT, std::uint64_t seed, std::uint64_t step,
                Add &&add) {
  constexpr std::size_t B = rng::batch;
  const double sigma = std::sqrt(kT);
  const std::size_t n = f.size();
  for (int k = 0; k < D; ++k)
    s.noise[k].resize(n);
  alignas(64) std::uint64_t tail[B];
  alignas(64) double g[4][B];
  for (std::size_t i0 = 0; i0 < n; i0 += B) {
    const std::size_t m = std::min(B, n - i0);
    const std::uint64_t *ids = f.id.data() + i0;
    if (m < B) {
      std::fill(std::copy(ids, ids + m, tail), tail + B, 0);
      ids = tail;
    }
    rng::gaussian_batch(seed, rng::Purpose::at_gaussian, step, ids, D == 2 ? 2 : 4, g);
    for (int k = 0; k < D; ++k) {
      double *xi = s.noise[k].data() + i0;
      for (std::size_t j = 0; j < m; ++j)
        xi[j] = sigma * g[k][j];
    }
    for (std::size_t i = i0; i < i0 + m; ++i)
      add(i);
  }
}

// Cells cut by a wall: the mean velocity and the mean noise include the virtual particles
// (their summed velocities and noise), delta = (P + P_v - X - X_v) / (n + n_v). The angular
// correction of MPC-AT+a stays over the real particles, whose positions alone are known.
template <int D>
void virtual_delta(const CellGrid &g, CollisionScratch &s, std::size_t sum_stride,
                   std::size_t par_stride) {
  for (const VirtualCell &v : g.virtual_cells) {
    const CellSums &c = g.sums[v.cell];
    if (c.n == 0)
      continue;
    const double inv_n = 1.0 / (c.n + v.count);
    for (int k = 0; k < D; ++k)
      s.cell[v.cell * par_stride + k] =
          (to_double(c.p[k]) + v.momentum[k] - to_double(s.cell_fixed[v.cell * sum_stride + k]) -
           v.noise[k]) *
          inv_n;
  }
}

// The groups' sums (grid.groups) that the AT rules add to the per-cell fixed-point sums: their
// xi (both rules) and, for AT+a (positions = true), their positions' first and second moments
// and angular momentum r x (v - xi), laid out as the particles' sums.
template <int D, int SS, bool positions>
void add_group_sums(const CellGrid &g, CollisionScratch &s) {
  for (const ParticleGroup &q : g.groups) {
    std::int64_t *sum = &s.cell_fixed[static_cast<std::size_t>(q.cell) * SS];
    for (int k = 0; k < D; ++k)
      sum[k] += from_double(q.xi[k]);
    if constexpr (positions) {
      for (int k = 0; k < D; ++k)
        sum[D + k] += from_double(q.r[k]);
      std::int64_t *m = sum + 2 * D;
      std::array<double, 9> w; // sum r_a (v - xi)_b
      for (int j = 0; j < 9; ++j)
        w[j] = q.rv[j] - q.rxi[j];
      if constexpr (D == 2) {
        m[0] += from_double(q.rr[0] + q.rr[4]);
        m[1] += from_double(w[1] - w[3]);
      } else {
        const int upper[6] = {0, 1, 2, 4, 5, 8}; // xx, xy, xz, yy, yz, zz
        for (int j = 0; j < 6; ++j)
          m[j] += from_double(q.rr[upper[j]]);
        m[6] += from_double(w[5] - w[7]);
        m[7] += from_double(w[6] - w[2]);
        m[8] += from_double(w[1] - w[3]);
      }
    }
  }
}

// A group's change when each of its particles gets v' = xi + delta + omega x (r - rc) (AT:
// omega = 0): the sums of v' - v and r_a (v'_b - v_b) from the group's moments.
template <int D>
void group_change(const ParticleGroup &q, const double *delta, const double *rc,
                  const double *omega, GroupChange &out) {
  // T_ad = sum r_a (r - rc)_d, and sum (r - rc).
  double T[3][3] = {}, c[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < D; ++a) {
    c[a] = q.r[a] - q.n * rc[a];
    for (int d = 0; d < D; ++d)
      T[a][d] = q.rr[3 * a + d] - q.r[a] * rc[d];
  }
  const double w[3] = {D == 3 ? omega[0] : 0.0, D == 3 ? omega[1] : 0.0,
                       D == 3 ? omega[2] : omega[0]};
  out.response = {};
  out.rc = {0.0, 0.0, 0.0};
  out.spin = {};
  for (int b = 0; b < D; ++b)
    out.response[4 * b] = 1.0; // v' = xi + u - <xi> (AT+a: + the rotation, spin below)
  for (int b = 0; b < D; ++b) {
    const int b1 = (b + 1) % 3, b2 = (b + 2) % 3; // (w x q)_b = w_b1 q_b2 - w_b2 q_b1
    out.v[b] = q.xi[b] + q.n * delta[b] + w[b1] * c[b2] - w[b2] * c[b1] - q.v[b];
    for (int a = 0; a < D; ++a)
      out.rv[3 * a + b] = q.rxi[3 * a + b] + q.r[a] * delta[b] + w[b1] * T[a][b2] -
                          w[b2] * T[a][b1] - q.rv[3 * a + b];
  }
}

template <int D>
void at_kernel(Fluid &f, const CellGrid &g, CollisionScratch &s, double kT, std::uint64_t seed,
               std::uint64_t step) {
  const std::size_t nc = g.size();
  s.cell_fixed.assign(nc * D, 0);
  const std::size_t n = f.size();
  draw_noise<D>(f, s, kT, seed, step, [&](std::size_t i) {
    prefetch_record<D, D>(s.cell_fixed, f.cell.data(), i, n);
    std::int64_t *sum = &s.cell_fixed[static_cast<std::size_t>(f.cell[i]) * D];
    for (int k = 0; k < D; ++k)
      sum[k] += from_double(s.noise[k][i]);
  });
  add_group_sums<D, D, false>(g, s);
  // Per cell: delta = u - <xi>, so that v' = xi + delta keeps the cell momentum.
  s.cell.resize(nc * D);
  for (std::size_t c = 0; c < nc; ++c) {
    const double inv_n = g.sums[c].n ? 1.0 / g.sums[c].n : 0.0;
    for (int k = 0; k < D; ++k)
      s.cell[c * D + k] = (to_double(g.sums[c].p[k]) - to_double(s.cell_fixed[c * D + k])) * inv_n;
  }
  virtual_delta<D>(g, s, D, D);
  s.group_change.resize(g.groups.size());
  const double none[3] = {0.0, 0.0, 0.0};
  for (std::size_t j = 0; j < g.groups.size(); ++j)
    group_change<D>(g.groups[j], &s.cell[g.groups[j].cell * D], none, none, s.group_change[j]);
  for (std::size_t i = 0; i < n; ++i) {
    prefetch_record<D, D>(s.cell, f.cell.data(), i, n);
    const double *delta = &s.cell[static_cast<std::size_t>(f.cell[i]) * D];
    for (int k = 0; k < D; ++k)
      f.v[k][i] = s.noise[k][i] + delta[k];
  }
}

inline double in_cell(double x, double shift) { return in_cell_offset(x, shift); }

// Fixed-point sums per cell for AT+a, laid out as
//   2D: xi(2) r(2) |r|^2 (1) r x (v - xi) (1)                              -> 6
//   3D: xi(3) r(3) r r^T(xx, xy, xz, yy, yz, zz) r x (v - xi)(3)           -> 15
// (2D needs only the trace of r r^T, and the angular momenta of v and xi only as a difference.)
template <int D> constexpr int sum_stride = D == 2 ? 6 : 15;
// delta(D) r_c(D) omega(1|3); with room, then a velocity change c(D) and spin w(1|3) that a
// coupling may give the cell between the cell loop and the particles (CollisionScratch::
// shift_offset; a fluid alone keeps the shorter records).
template <int D, bool room> constexpr int par_stride = D == 2 ? (room ? 8 : 5) : (room ? 15 : 9);
template <int D> constexpr int shift_offset = D == 2 ? 5 : 9;

template <int D> inline void cross(const double *a, const double *b, double *out) {
  if constexpr (D == 2) {
    out[0] = a[0] * b[1] - a[1] * b[0];
  } else {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  }
}

// Pseudo-inverse of a cell's moment of inertia: with two particles (or collinear ones) I has a
// zero eigenvalue along their line, and dL has no component there, so dropping it is exact.
// compute(), not computeDirect(): the closed form loses ~8 digits on the double eigenvalue of
// two-particle cells. The absolute floor keeps round-off (~1e-12) in a null direction from being
// inverted into a spurious rotation.
Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d &I) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  const Eigen::Vector3d lam = eig.eigenvalues();
  const double cut = std::max(1e-10 * lam.cwiseAbs().maxCoeff(), 1e-11);
  Eigen::Vector3d inv;
  for (int k = 0; k < 3; ++k)
    inv[k] = std::abs(lam[k]) > cut ? 1.0 / lam[k] : 0.0;
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

// The adjugate and determinant of a cell's moment of inertia I (symmetric: its upper entries),
// and whether I is well conditioned enough to be inverted through them: det >= 1e-4 (tr/3)^3,
// tr = 2 t with t = tr S, bounds its condition number by 27e4.
struct Adjugate {
  double A00, A01, A02, A11, A12, A22, det;
  bool usable;
};
inline Adjugate adjugate(double I00, double I01, double I02, double I11, double I12, double I22,
                         double t) {
  Adjugate a;
  a.A00 = I11 * I22 - I12 * I12;
  a.A01 = I02 * I12 - I01 * I22;
  a.A02 = I01 * I12 - I02 * I11;
  a.A11 = I00 * I22 - I02 * I02;
  a.A12 = I01 * I02 - I00 * I12;
  a.A22 = I00 * I11 - I01 * I01;
  a.det = I00 * a.A00 + I01 * a.A01 + I02 * a.A02;
  const double tr3 = 2.0 * t / 3.0;
  a.usable = tr3 > 1e-6 && a.det > 1e-4 * tr3 * tr3 * tr3;
  return a;
}

// MPC-AT+a up to the new velocities: the noise, the cell sums and records, the groups' change.
template <int D, bool room>
void at_a_cells(Fluid &f, const CellGrid &g, CollisionScratch &s, double kT, std::uint64_t seed,
                std::uint64_t step) {
  constexpr int SS = sum_stride<D>, PS = par_stride<D, room>, NL = D == 2 ? 1 : 3;
  constexpr int NM = D == 2 ? 1 : 6; // entries of r r^T summed
  const std::size_t nc = g.size(), n = f.size();
  s.cell_fixed.assign(nc * SS, 0);
  // One pass: the noise of a batch, then its particles' sums.
  draw_noise<D>(f, s, kT, seed, step, [&](std::size_t i) {
    prefetch_record<D, SS>(s.cell_fixed, f.cell.data(), i, n);
    std::int64_t *sum = &s.cell_fixed[static_cast<std::size_t>(f.cell[i]) * SS];
    double r[3], w[3], l[3];
    for (int k = 0; k < D; ++k) {
      const double xi = s.noise[k][i];
      r[k] = in_cell(f.x[k][i], g.shift[k]);
      w[k] = f.v[k][i] - xi;
      sum[k] += from_double(xi);
      sum[D + k] += from_double(r[k]);
    }
    std::int64_t *m = sum + 2 * D;
    if constexpr (D == 2) {
      m[0] += from_double(r[0] * r[0] + r[1] * r[1]);
    } else {
      m[0] += from_double(r[0] * r[0]);
      m[1] += from_double(r[0] * r[1]);
      m[2] += from_double(r[0] * r[2]);
      m[3] += from_double(r[1] * r[1]);
      m[4] += from_double(r[1] * r[2]);
      m[5] += from_double(r[2] * r[2]);
    }
    cross<D>(r, w, l);
    for (int k = 0; k < NL; ++k)
      m[NM + k] += from_double(l[k]);
  });
  add_group_sums<D, SS, true>(g, s);

  s.cell.resize(nc * PS); // (an empty cell's record is never read: no fill)
  for (std::size_t c = 0; c < nc; ++c) {
    const std::int64_t *sum = &s.cell_fixed[c * SS];
    double *par = &s.cell[c * PS];
    const std::uint32_t cnt = g.sums[c].n;
    if (cnt == 0)
      continue;
    if constexpr (room)
      for (int k = shift_offset<D>; k < PS; ++k) // (no coupling's change yet)
        par[k] = 0.0;
    const double inv_n = 1.0 / cnt;
    double P[3], X[3], rc[3];
    for (int k = 0; k < D; ++k) {
      P[k] = to_double(g.sums[c].p[k]);
      X[k] = to_double(sum[k]);
      rc[k] = to_double(sum[D + k]) * inv_n;
      par[k] = (P[k] - X[k]) * inv_n; // delta = u - <xi>
      par[D + k] = rc[k];
    }
    // Angular momentum about the cell's centre of mass that the AT step would destroy:
    // dL = sum (r - rc) x (v - xi) = sum r x (v - xi) - rc x (P - X).
    double PX[3], rcPX[3];
    for (int k = 0; k < D; ++k)
      PX[k] = P[k] - X[k];
    cross<D>(rc, PX, rcPX);
    double dL[3];
    for (int k = 0; k < NL; ++k)
      dL[k] = to_double(sum[2 * D + NM + k]) - rcPX[k];
    if constexpr (D == 2) {
      // I = sum |r - rc|^2 = sum |r|^2 - n |rc|^2
      const double I = to_double(sum[4]) - cnt * (rc[0] * rc[0] + rc[1] * rc[1]);
      par[4] = I > 1e-12 ? dL[0] / I : 0.0; // one particle, or all at one point: dL = 0
    } else {
      const std::int64_t *m = sum + 6;
      // Second moment about rc, S = sum (r - rc)(r - rc)^T, and I = tr(S) 1 - S.
      const double S00 = to_double(m[0]) - cnt * rc[0] * rc[0],
                   S01 = to_double(m[1]) - cnt * rc[0] * rc[1],
                   S02 = to_double(m[2]) - cnt * rc[0] * rc[2],
                   S11 = to_double(m[3]) - cnt * rc[1] * rc[1],
                   S12 = to_double(m[4]) - cnt * rc[1] * rc[2],
                   S22 = to_double(m[5]) - cnt * rc[2] * rc[2];
      const double t = S00 + S11 + S22;
      const double I00 = t - S00, I11 = t - S11, I22 = t - S22, I01 = -S01, I02 = -S02, I12 = -S12;
      // Adjugate and determinant. A cell of three or more particles off one line has a
      // well-conditioned I: det >= 1e-4 (tr/3)^3 bounds its condition number by 27e4, and
      // the inverse from the adjugate, refined once against the residual, solves I w = dL to
      // round-off (the eigen-decomposition below costs ~1 us a cell, most of a 3D step).
      const auto [A00, A01, A02, A11, A12, A22, det, usable] =
          adjugate(I00, I01, I02, I11, I12, I22, t);
      Eigen::Vector3d w;
      if (usable) {
        const double inv = 1.0 / det;
        const auto solve = [&](const double *b, double *x) {
          x[0] = (A00 * b[0] + A01 * b[1] + A02 * b[2]) * inv;
          x[1] = (A01 * b[0] + A11 * b[1] + A12 * b[2]) * inv;
          x[2] = (A02 * b[0] + A12 * b[1] + A22 * b[2]) * inv;
        };
        double x[3], res[3], dx[3];
        solve(dL, x);
        res[0] = dL[0] - (I00 * x[0] + I01 * x[1] + I02 * x[2]);
        res[1] = dL[1] - (I01 * x[0] + I11 * x[1] + I12 * x[2]);
        res[2] = dL[2] - (I02 * x[0] + I12 * x[1] + I22 * x[2]);
        solve(res, dx);
        w = Eigen::Vector3d(x[0] + dx[0], x[1] + dx[1], x[2] + dx[2]);
      } else {
        Eigen::Matrix3d I;
        I << I00, I01, I02, I01, I11, I12, I02, I12, I22;
        w = pseudo_inverse(I) * Eigen::Vector3d(dL[0], dL[1], dL[2]);
      }
      par[6] = w[0];
      par[7] = w[1];
      par[8] = w[2];
    }
  }
  virtual_delta<D>(g, s, SS, PS);
  s.group_change.resize(g.groups.size());
  for (std::size_t j = 0; j < g.groups.size(); ++j) {
    const std::size_t cell = g.groups[j].cell;
    const double *par = &s.cell[cell * PS];
    GroupChange &out = s.group_change[j];
    group_change<D>(g.groups[j], par, par + D, par + 2 * D, out);
    // The cell's rc and inverse moment of inertia, for the implicit exchange.
    const std::int64_t *sum = &s.cell_fixed[cell * SS];
    const double cnt = g.sums[cell].n;
    out.spin = {};
    out.rc = {0.0, 0.0, 0.0};
    for (int k = 0; k < D; ++k)
      out.rc[k] = par[D + k];
    const double *rc = par + D;
    if constexpr (D == 2) {
      const double I = to_double(sum[4]) - cnt * (rc[0] * rc[0] + rc[1] * rc[1]);
      out.spin[8] = I > 1e-12 ? 1.0 / I : 0.0;
    } else {
      const std::int64_t *m = sum + 6;
      const int idx[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
      Eigen::Matrix3d S, I;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          S(a, b) = to_double(m[idx[a][b]]) - cnt * rc[a] * rc[b];
      I = S.trace() * Eigen::Matrix3d::Identity() - S;
      // A well-conditioned I (the test of the cell loop above) is inverted from its adjugate
      // and refined once, X + X (1 - I X); the others by the eigen-decomposition. (A 3D channel
      // of 752 spheres has ~5e4 groups a step: the decomposition of each was 11 % of its loop.)
      const Adjugate adj =
          adjugate(I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), S.trace());
      Eigen::Matrix3d P;
      if (adj.usable) {
        const Eigen::Matrix3d A{
            {adj.A00, adj.A01, adj.A02}, {adj.A01, adj.A11, adj.A12}, {adj.A02, adj.A12, adj.A22}};
        const double det = adj.det;
        const Eigen::Matrix3d X = A / det;
        P = X + X * (Eigen::Matrix3d::Identity() - I * X);
        P = 0.5 * (P + P.transpose()).eval(); // (symmetric, as I)
      } else {
        P = pseudo_inverse(I);
      }
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          out.spin[3 * a + b] = P(a, b);
    }
  }

  s.position_stride = SS;
  s.position_offset = D;
  s.cells_pending = true;
  s.shift_stride = room ? PS : 0;
  s.shift_offset = shift_offset<D>;
  s.cells_shifted = false;
  // GCC 12 (-march=native, AVX-512) vectorises the 2D cell loop above with ymm registers and
  // leaves them dirty on return (no vzeroupper, unlike every other kernel). Each later call
  // into libm's SSE-encoded code (the log of the next step's noise, the sines of a sine
  // force) then paid a state-transition penalty: log took ~220 ns instead of ~15 ns, half of
  // an AT+a run's time. Clearing the upper halves changes no value (they are dead here).
#if defined(__AVX__)
  __builtin_ia32_vzeroupper();
#endif
}

// The new velocities, v' = xi + delta + omega x (r - rc); with `shifted`, plus the velocity
// change c + w x r' (r' from the cell's corner) that a coupling wrote into the cell's record
// after the cell loop, exactly as a pass of its own over the new velocities would add it.
template <int D, bool room, bool shifted>
void at_a_particles(Fluid &f, const CellGrid &g, CollisionScratch &s) {
  static_assert(room || !shifted);
  constexpr int PS = par_stride<D, room>, SO = shift_offset<D>;
  const std::size_t n = f.size();
  double v2_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    prefetch_record<D, PS>(s.cell, f.cell.data(), i, n);
    const double *par = &s.cell[static_cast<std::size_t>(f.cell[i]) * PS];
    double r[3], corner[3];
    for (int k = 0; k < D; ++k) {
      corner[k] = in_cell(f.x[k][i], g.shift[k]);
      r[k] = corner[k] - par[D + k];
    }
    double v[3];
    if constexpr (D == 2) {
      v[0] = s.noise[0][i] + par[0] - par[4] * r[1];
      v[1] = s.noise[1][i] + par[1] + par[4] * r[0];
      if constexpr (shifted) {
        v[0] += par[SO] - par[SO + 2] * corner[1];
        v[1] += par[SO + 1] + par[SO + 2] * corner[0];
      }
    } else {
      double wr[3];
      cross<3>(par + 6, r, wr);
      for (int k = 0; k < 3; ++k)
        v[k] = s.noise[k][i] + par[k] + wr[k];
      if constexpr (shifted) {
        double ws[3];
        cross<3>(par + SO + 3, corner, ws);
        for (int k = 0; k < 3; ++k)
          v[k] += par[SO + k] + ws[k];
      }
    }
    double v2 = 0.0;
    for (int k = 0; k < D; ++k) {
      f.v[k][i] = v[k];
      v2 += v[k] * v[k];
    }
    v2_max = std::max(v2_max, v2);
  }
  s.v2_max = v2_max;
  s.cells_pending = false;
  s.shift_stride = 0;
  s.cells_shifted = false;
  // (as at_a_cells: no dirty upper halves on return)
#if defined(__AVX__)
  __builtin_ia32_vzeroupper();
#endif
}

} // namespace

void collide_at(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double kT,
                std::uint64_t seed, std::uint64_t step) {
  scratch.position_stride = 0;
  if (grid.dim == 3)
    at_kernel<3>(fluid, grid, scratch, kT, seed, step);
  else
    at_kernel<2>(fluid, grid, scratch, kT, seed, step);
}

void collide_at_a_cells(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double kT,
                        std::uint64_t seed, std::uint64_t step, bool room_for_shifts) {
  if (grid.dim == 3)
    room_for_shifts ? at_a_cells<3, true>(fluid, grid, scratch, kT, seed, step)
                    : at_a_cells<3, false>(fluid, grid, scratch, kT, seed, step);
  else
    room_for_shifts ? at_a_cells<2, true>(fluid, grid, scratch, kT, seed, step)
                    : at_a_cells<2, false>(fluid, grid, scratch, kT, seed, step);
}

void collide_at_a_particles(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch) {
  if (!scratch.cells_pending)
    throw std::logic_error("collide_at_a_particles: the cells of this step were not collided");
  const bool room = scratch.shift_stride > 0, shifted = scratch.cells_shifted;
  if (shifted && !room)
    throw std::logic_error("collide_at_a_particles: cells shifted without room in the records");
  if (grid.dim == 3)
    shifted ? at_a_particles<3, true, true>(fluid, grid, scratch)
    : room  ? at_a_particles<3, true, false>(fluid, grid, scratch)
            : at_a_particles<3, false, false>(fluid, grid, scratch);
  else
    shifted ? at_a_particles<2, true, true>(fluid, grid, scratch)
    : room  ? at_a_particles<2, true, false>(fluid, grid, scratch)
            : at_a_particles<2, false, false>(fluid, grid, scratch);
}

void collide_at_a(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double kT,
                  std::uint64_t seed, std::uint64_t step) {
  collide_at_a_cells(fluid, grid, scratch, kT, seed, step, false);
  collide_at_a_particles(fluid, grid, scratch);
}

} // namespace narrows::mpcd
