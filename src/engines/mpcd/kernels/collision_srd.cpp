// Stochastic rotation dynamics (Tabatabaei (2008) eq 3.4-3.8).
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/core/rng_batch.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace narrows::mpcd {

namespace {

// Per-cell parameters: 2D {ux, uy, cos, +-sin}; 3D {ux, uy, uz, ax, ay, az, cos - 1, sin}
// (the axis a and Rodrigues' form of the rotation; cos - 1 = sin = 0 is the identity). A 3D
// record is 64 bytes, one cache line: the parameter array starts on a line boundary.
template <int D> constexpr int stride = D == 2 ? 4 : 8;

// The first 64-byte boundary inside `par`, which has room for nc records plus one line.
inline double *aligned_records(std::vector<double> &par, std::size_t nc, int stride) {
  par.resize(nc * stride + 8);
  const auto addr = reinterpret_cast<std::uintptr_t>(par.data());
  return par.data() + ((64 - addr % 64) % 64) / sizeof(double);
}

// The rotation of one cell: 2D {cos, +-sin}; 3D {axis, cos - 1, sin} about a random axis
// uniform on the sphere (Tabatabaei (2008) eq 3.8), drawn by Marsaglia's method: (u, v) uniform in
// the unit disc, s = u^2 + v^2, axis = (2u sqrt(1 - s), 2v sqrt(1 - s), 1 - 2s). One Philox block
// gives two tries; the rare third and later tries (4.6 %) use further blocks.
template <int D>
void set_rotation(double *rot, double ca, double sa, std::uint64_t seed, std::uint64_t step,
                  std::uint64_t cell_id, rng::Block r) {
  if constexpr (D == 2) {
    rot[0] = ca;
    rot[1] = (r[0] & 1u) ? sa : -sa;
  } else {
    for (std::uint64_t attempt = 1;; ++attempt) {
      for (int t = 0; t < 4; t += 2) {
        const double u = 2.0 * rng::open01(r[t]) - 1.0, v = 2.0 * rng::open01(r[t + 1]) - 1.0;
        const double q = u * u + v * v;
        if (q < 1.0) {
          const double h = 2.0 * std::sqrt(1.0 - q);
          rot[0] = u * h;
          rot[1] = v * h;
          rot[2] = 1.0 - 2.0 * q;
          rot[3] = ca - 1.0;
          rot[4] = sa;
          return;
        }
      }
      r = rng::draw(seed, rng::Purpose::srd_rotation_retry, step, cell_id ^ (attempt << 56));
    }
  }
}
template <int D>
void set_rotation(double *rot, double ca, double sa, std::uint64_t seed, std::uint64_t step,
                  std::uint64_t cell_id) {
  set_rotation<D>(rot, ca, sa, seed, step, cell_id,
                  rng::draw(seed, rng::Purpose::srd_rotation, step, cell_id));
}

// The cells a batch at a time: their first Philox blocks drawn together (rng::draw_batch, the
// same words as rng::draw), and their global ids counted along (global_id divides).
template <int D>
void srd_cells(const CellGrid &g, std::vector<double> &par, double angle, std::uint64_t seed,
               std::uint64_t step) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  const std::size_t nc = g.size();
  double *base = aligned_records(par, nc, stride<D>);
  constexpr std::size_t B = rng::batch;
  const auto nx = static_cast<std::size_t>(g.cells[0]);
  std::uint64_t ids[B];
  std::uint32_t w[4][B];
  std::size_t column = 0, line = 0; // of cell c0: c0 = column + nx line
  for (std::size_t c0 = 0; c0 < nc; c0 += B) {
    const std::size_t m = std::min(B, nc - c0);
    for (std::size_t j = 0; j < B; ++j) {
      ids[j] = column + static_cast<std::size_t>(g.first_column) +
               static_cast<std::uint64_t>(g.global_columns) * line; // (padded lanes: unused)
      if (++column == nx) {
        column = 0;
        ++line;
      }
    }
    rng::draw_batch(seed, rng::Purpose::srd_rotation, step, ids, w);
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t c = c0 + j;
      const CellSums &s = g.sums[c];
      double *p = base + c * stride<D>;
      const double inv_n = s.n ? 1.0 / s.n : 0.0;
      for (int k = 0; k < D; ++k)
        p[k] = fixed::to_double(s.p[k]) * inv_n;
      if (s.n < 2) { // nothing to mix: the identity
        if constexpr (D == 2) {
          p[2] = 1.0;
          p[3] = 0.0;
        } else {
          for (int k = 3; k < 8; ++k)
            p[k] = 0.0;
        }
        continue;
      }
      set_rotation<D>(p + D, ca, sa, seed, step, ids[j], {w[0][j], w[1][j], w[2][j], w[3][j]});
    }
  }
  // Cells cut by a wall: the mean velocity includes the virtual particles (Tabatabaei (2008)
  // eq 3.14), and a lone real particle is mixed with them too.
  for (const VirtualCell &v : g.virtual_cells) {
    const CellSums &s = g.sums[v.cell];
    if (s.n == 0)
      continue;
    double *p = base + v.cell * stride<D>;
    const double inv_n = 1.0 / (s.n + v.count);
    for (int k = 0; k < D; ++k)
      p[k] = (fixed::to_double(s.p[k]) + v.momentum[k]) * inv_n;
    if (s.n == 1)
      set_rotation<D>(p + D, ca, sa, seed, step, g.global_id(v.cell));
  }
}

// Each group's change: every particle gets v' - v = A (v - u), with A = R - 1 the cell's
// rotation less the identity (zero in a cell left unrotated).
template <int D>
void srd_groups(const CellGrid &g, std::vector<double> &par, std::vector<GroupChange> &change) {
  const double *base = aligned_records(par, g.size(), stride<D>);
  change.resize(g.groups.size());
  for (std::size_t j = 0; j < g.groups.size(); ++j) {
    const ParticleGroup &q = g.groups[j];
    const double *p = base + static_cast<std::size_t>(q.cell) * stride<D>;
    double A[3][3] = {};
    if constexpr (D == 2) {
      A[0][0] = A[1][1] = p[2] - 1.0;
      A[0][1] = -p[3];
      A[1][0] = p[3];
    } else { // A w = (cos - 1)(w - (a.w) a) + sin (a x w)
      const double *ax = p + 3, c1 = p[6], s1 = p[7];
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c)
          A[b][c] = c1 * ((b == c ? 1.0 : 0.0) - ax[b] * ax[c]);
      A[0][1] -= s1 * ax[2];
      A[0][2] += s1 * ax[1];
      A[1][0] += s1 * ax[2];
      A[1][2] -= s1 * ax[0];
      A[2][0] -= s1 * ax[1];
      A[2][1] += s1 * ax[0];
    }
    // W = sum (v - u) and sum r_a (v - u)_c; the change is A applied to each.
    double W[3], RW[3][3];
    for (int c = 0; c < D; ++c) {
      W[c] = q.v[c] - q.n * p[c];
      for (int a = 0; a < D; ++a)
        RW[a][c] = q.rv[3 * a + c] - q.r[a] * p[c];
    }
    GroupChange &out = change[j];
    out.response = {};
    out.rc = {0.0, 0.0, 0.0};
    out.spin = {};
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        out.response[3 * b + c] = -A[b][c];
    for (int b = 0; b < D; ++b) {
      out.v[b] = 0.0;
      for (int c = 0; c < D; ++c)
        out.v[b] += A[b][c] * W[c];
      for (int a = 0; a < D; ++a) {
        double t = 0.0;
        for (int c = 0; c < D; ++c)
          t += A[b][c] * RW[a][c];
        out.rv[3 * a + b] = t;
      }
    }
  }
}

// v' = u + R (v - u) for m particles (distinct arrays: restrict lets the loop vectorise, the
// records gathered).
template <int D>
void rotate_block(double *__restrict vx, double *__restrict vy, double *__restrict vz,
                  const std::uint32_t *__restrict cell, const double *__restrict base,
                  std::size_t m) {
  for (std::size_t i = 0; i < m; ++i) {
    // (indexed from base with a signed 32-bit offset: so GCC gathers; the records' doubles stay
    // below 2^31)
    const auto c = static_cast<std::int32_t>(cell[i] * stride<D>);
    if constexpr (D == 2) {
      const double ux = base[c], uy = base[c + 1], ca = base[c + 2], sa = base[c + 3];
      const double wx = vx[i] - ux, wy = vy[i] - uy;
      vx[i] = ux + ca * wx - sa * wy;
      vy[i] = uy + sa * wx + ca * wy;
    } else {
      // v' = u + R w = v + (cos - 1)(w - (a.w) a) + sin (a x w), w = v - u.
      const double wx = vx[i] - base[c], wy = vy[i] - base[c + 1], wz = vz[i] - base[c + 2];
      const double ax = base[c + 3], ay = base[c + 4], az = base[c + 5], c1 = base[c + 6],
                   s1 = base[c + 7];
      const double aw = ax * wx + ay * wy + az * wz;
      vx[i] += c1 * (wx - aw * ax) + s1 * (ay * wz - az * wy);
      vy[i] += c1 * (wy - aw * ay) + s1 * (az * wx - ax * wz);
      vz[i] += c1 * (wz - aw * az) + s1 * (ax * wy - ay * wx);
    }
  }
}

template <int D> void srd_particles(Fluid &f, std::vector<double> &par, std::size_t nc) {
  double *vx = f.v[0].data(), *vy = f.v[1].data(), *vz = f.v[2].data();
  const std::uint32_t *cell = f.cell.data();
  const std::size_t n = f.size();
  const double *base = aligned_records(par, nc, stride<D>);
  // Records of later particles are fetched ahead: the loop is bound by their latency (at 1e6
  // particles, one core: 3D 12.0 -> 6.0 ns per particle, 2D 4.1 -> 3.7 ns). A block's records
  // are fetched while the block before it is rotated.
  constexpr std::size_t block = 64;
  for (std::size_t i0 = 0; i0 < n; i0 += block) {
    const std::size_t m = std::min(block, n - i0);
    for (std::size_t i = i0 + block; i < std::min(n, i0 + 2 * block); ++i)
      __builtin_prefetch(base + static_cast<std::size_t>(cell[i]) * stride<D>);
    rotate_block<D>(vx + i0, vy + i0, D == 3 ? vz + i0 : nullptr, cell + i0, base, m);
  }
}

} // namespace

void collide_srd(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double angle_rad,
                 std::uint64_t seed, std::uint64_t step) {
  scratch.position_stride = 0;
  if (grid.dim == 3) {
    srd_cells<3>(grid, scratch.cell, angle_rad, seed, step);
    srd_groups<3>(grid, scratch.cell, scratch.group_change);
    srd_particles<3>(fluid, scratch.cell, grid.size());
  } else {
    srd_cells<2>(grid, scratch.cell, angle_rad, seed, step);
    srd_groups<2>(grid, scratch.cell, scratch.group_change);
    srd_particles<2>(fluid, scratch.cell, grid.size());
  }
}

} // namespace narrows::mpcd
