// Ghost particles inside no-slip colloids for the collision step (Kanehl (thesis) §4.2.1, eq 4.18).
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/core/rng_batch.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/coupling/ghost_response.hpp"
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace narrows::coupling {

using namespace narrows::colloids;

namespace {

// How many groups ahead their cell sums are fetched.
constexpr std::size_t prefetch_ahead = 8;

// The key of a ghost particle's draws: colloid id, global cell, try (255: the fractional try).
std::uint64_t ghost_key(std::uint64_t colloid, std::uint64_t cell, std::uint64_t t) {
  return (colloid << 40) | (cell << 8) | t;
}

// Groups computed side by side, one per vector lane.
constexpr int lanes = 8;

// Cholesky factor L (lower, m x m) of the positive semi-definite moment matrix M of a group,
// M = sum (1, r)(1, r)^T, for `lanes` groups at once ([row][column][lane]). A pivot that
// vanishes to round-off against its diagonal (one ghost, or ghosts on a line) leaves its column
// zero: for a semi-definite M the column below it vanishes too, so L L^T = M still and L z has
// covariance M. (Each lane's operations are those of one group alone, in the same order: the
// square roots and quotients a group waited on in turn now overlap across the lanes.)
template <int m> void cholesky(const double (&M)[m][m][lanes], double (&L)[m][m][lanes]) {
  for (int j = 0; j < m; ++j) {
    double d[lanes], root[lanes];
    bool pivot[lanes];
    for (int l = 0; l < lanes; ++l)
      d[l] = M[j][j][l];
    for (int k = 0; k < j; ++k)
      for (int l = 0; l < lanes; ++l)
        d[l] -= L[j][k][l] * L[j][k][l];
    for (int l = 0; l < lanes; ++l) {
      pivot[l] = d[l] > 1e-10 * M[j][j][l];
      root[l] = std::sqrt(pivot[l] ? d[l] : 1.0);
      L[j][j][l] = pivot[l] ? root[l] : 0.0;
    }
    for (int i = j + 1; i < m; ++i) {
      double t[lanes];
      for (int l = 0; l < lanes; ++l)
        t[l] = M[i][j][l];
      for (int k = 0; k < j; ++k)
        for (int l = 0; l < lanes; ++l)
          t[l] -= L[i][k][l] * L[j][k][l];
      for (int l = 0; l < lanes; ++l)
        L[i][j][l] = pivot[l] ? t[l] / root[l] : 0.0;
    }
    for (int i = 0; i < j; ++i) // (above the diagonal: zero)
      for (int l = 0; l < lanes; ++l)
        L[i][j][l] = 0.0;
  }
}

// What a batch of groups needs and gives ([...][lane]): in, their sums and their colloid's
// motion; out, the ghosts' velocity sums (ParticleGroup's v, rv, xi, rxi).
struct GroupBatch {
  alignas(64) double n[lanes], r[3][lanes], rr[9][lanes], corner[3][lanes];
  alignas(64) double U[3][lanes], W[3][lanes];
  alignas(64) double z[2][12][lanes]; // eta's (1 + D) D standard normals, then xi's
  alignas(64) double v[3][lanes], rv[9][lanes], xi[3][lanes], rxi[9][lanes];
};

// The Gaussian sums of the groups' eta and xi at kT = sigma^2: for each component b, sigma L z
// with z m standard normals; then v = sum (U + W x r' + eta) and sum r (U + W x r' + eta)^T with
// r' = c' + r, c' the cell corner from the colloid's centre.
template <int m> [[gnu::noinline]] void group_velocities(GroupBatch &g, double sigma) {
  constexpr int D = m - 1;
  double M[m][m][lanes], L[m][m][lanes];
  for (int l = 0; l < lanes; ++l)
    M[0][0][l] = g.n[l];
  for (int i = 0; i < D; ++i) {
    for (int l = 0; l < lanes; ++l)
      M[0][1 + i][l] = M[1 + i][0][l] = g.r[i][l];
    for (int j = 0; j < D; ++j)
      for (int l = 0; l < lanes; ++l)
        M[1 + i][1 + j][l] = g.rr[3 * i + j][l];
  }
  cholesky<m>(M, L);
  double eta[3][4][lanes], xi[3][4][lanes]; // [b][0]: sum, [b][1 + a]: sum r_a, of component b
  for (int b = 0; b < D; ++b)
    for (int i = 0; i < m; ++i) {
      double e[lanes], x[lanes];
      for (int l = 0; l < lanes; ++l)
        e[l] = x[l] = 0.0;
      for (int k = 0; k <= i; ++k)
        for (int l = 0; l < lanes; ++l) {
          e[l] += L[i][k][l] * g.z[0][b * m + k][l];
          x[l] += L[i][k][l] * g.z[1][b * m + k][l];
        }
      for (int l = 0; l < lanes; ++l) {
        eta[b][i][l] = sigma * e[l];
        xi[b][i][l] = sigma * x[l];
      }
    }
  // sum r' = N c' + sum r; v = U + W x r' + eta.
  double first[3][lanes];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < lanes; ++l)
      first[k][l] = g.n[l] * g.corner[k][l] + g.r[k][l];
  for (int b = 0; b < D; ++b) {
    const int b1 = (b + 1) % 3, b2 = (b + 2) % 3; // (W x y)_b = W_b1 y_b2 - W_b2 y_b1
    for (int l = 0; l < lanes; ++l) {
      g.v[b][l] =
          g.n[l] * g.U[b][l] + g.W[b1][l] * first[b2][l] - g.W[b2][l] * first[b1][l] + eta[b][0][l];
      g.xi[b][l] = xi[b][0][l];
    }
    for (int k = 0; k < D; ++k)
      for (int l = 0; l < lanes; ++l) {
        const double spin_corner = g.W[b1][l] * g.corner[b2][l] - g.W[b2][l] * g.corner[b1][l];
        g.rv[3 * k + b][l] = g.r[k][l] * (g.U[b][l] + spin_corner) +
                             g.W[b1][l] * g.rr[3 * k + b2][l] - g.W[b2][l] * g.rr[3 * k + b1][l] +
                             eta[b][1 + k][l];
        g.rxi[3 * k + b][l] = xi[b][1 + k][l];
      }
  }
}

} // namespace

// Why sums suffice, and why they are exact in distribution. A ghost g of colloid (X, U, Omega)
// in a cut cell sits at r_g (offset from the cell's corner c, so r' = c - X + r_g from the
// centre) with v_g = U + Omega x r' + eta_g, eta_g Gaussian at kT; the MPC-AT rules also give it
// a Gaussian xi_g at kT. Every rule's v' is affine in (v, xi, r) within a cell, so the
// collision needs of a colloid's ghosts in a cell only N, sum r, sum r r^T, sum v, sum r v^T,
// sum xi, sum r xi^T, and gives back sum (v' - v), sum r (v' - v)^T: the impulse and, about X,
// the angular impulse. Given the positions, each component b of (sum eta, sum r eta^T) is
// Gaussian with covariance kT M, M = sum (1, r)(1, r)^T, independent across b; so is that of
// xi. One Cholesky factor of M per pair, and (1 + D) D standard normals each for eta and xi,
// give exactly the distribution of the per-ghost draws. The positions keep their tries (n a
// cell, uniform, kept inside the colloid and the channel), so N and the moments are those of
// particles placed one by one.
void NoSlipCoupling::add_ghost_particles(mpcd::CellGrid &grid, const Colloids &c,
                                         std::uint64_t step) {
  const ScopedSeconds timed(seconds_);
  const ScopedSeconds stage(stage_seconds_[ghost_sums]);
  grid.groups.clear();
  group_row_.clear();
  group_corner_.clear();
  group_key_.clear();
  std::size_t ghosts = 0; // (ghost_count_, counted in a register)
  const double n = params_.density;
  const int whole = static_cast<int>(std::floor(n));
  const double fraction = n - whole;
  const int NX = grid.global_columns, nx = grid.cells[0], ny = grid.cells[1], nz = grid.cells[2];
  const bool walls = grid.walls_y;
  const double *sh = grid.shift.data();
  const int per_block = dim_ == 2 ? 2 : 1;
  // 1. The cut cells: (colloid row, local cell, global cell, corner from the centre). Every
  // cell of a colloid's box is written and the count advanced only for a cut one: half of them
  // are, at random, and a branch on it was mispredicted as often.
  std::size_t cuts = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double R = c.radius[a], R2 = R * R;
    const double X[3] = {c.x[0][a], c.x[1][a], dim_ == 3 ? c.x[2][a] : 0.0};
    // Cells of the shifted grid that the colloid's bounding box touches, as unwrapped indices:
    // along x and z (and y without walls) cell i covers [i + s, i + 1 + s); with walls row j
    // covers [j - 1 + s, j + s).
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < dim_; ++k) {
      const double s = sh[k];
      lo[k] = static_cast<int>(std::floor(X[k] - R - s));
      hi[k] = static_cast<int>(std::floor(X[k] + R - s));
      if (k == 1 && walls) {
        lo[k] = std::max(lo[k] + 1, 0);
        hi[k] = std::min(hi[k] + 1, ny - 1);
      }
    }
    std::size_t box_cells = 1;
    for (int k = 0; k < dim_; ++k)
      box_cells *= static_cast<std::size_t>(std::max(hi[k] - lo[k] + 1, 0));
    if (cut_.size() < cuts + box_cells)
      cut_.resize(std::max(cuts + box_cells, 2 * cut_.size()));
    for (int i = lo[0]; i <= hi[0]; ++i) {
      const int column = wrap_index(i, NX);
      const int ix = column - grid.first_column;
      if (ix < 0 || ix >= nx)
        continue;
      for (int j = lo[1]; j <= hi[1]; ++j) {
        const int row = walls ? j : wrap_index(j, ny);
        for (int l = lo[2]; l <= hi[2]; ++l) {
          const int layer = dim_ == 3 ? wrap_index(l, nz) : 0;
          // The cell's lower corner relative to the centre (unwrapped), and its classification:
          // outside the colloid, wholly inside (no fluid can be there), or cut by the surface.
          const double corner[3] = {i + sh[0] - X[0], (walls ? j - 1 : j) + sh[1] - X[1],
                                    dim_ == 3 ? l + sh[2] - X[2] : 0.0};
          double near2 = 0.0, far2 = 0.0;
          for (int k = 0; k < dim_; ++k) {
            const double q = std::clamp(0.0, corner[k], corner[k] + 1.0);
            near2 += q * q;
            far2 += std::max(corner[k] * corner[k], (corner[k] + 1.0) * (corner[k] + 1.0));
          }
          const std::size_t above = row + static_cast<std::size_t>(ny) * layer;
          const std::size_t cell = ix + static_cast<std::size_t>(nx) * above;
          // (grid.global_id(cell), without its division)
          const std::uint64_t global = column + static_cast<std::uint64_t>(NX) * above;
          cut_[cuts] = {static_cast<std::uint32_t>(a),
                        static_cast<std::uint32_t>(cell),
                        ghost_key(c.id[a], global, 0),
                        {corner[0], corner[1], corner[2]}};
          cuts += (near2 < R2) & (far2 > R2); // bitwise &: no branch
        }
      }
    }
  }
  // 2. The kept tries' moments per cut cell: count, sum r, sum r r^T (r from the cell's
  // corner), a try kept if inside the colloid (and the channel). A batch of cells at a time, one
  // cell per lane (each cell's sums add up in the order of its tries, bitwise those of one cell
  // after another, and the loop over the lanes vectorises): first the block of the fractional
  // try (255), which decides whether a cell makes whole or whole + 1 tries; then the blocks of
  // the tries, keyed by the block's first try (2D: two tries a block, words 0-1 and 2-3; 3D:
  // one, words 0-2); summed without branches (half the tries are dropped, at random).
  const int blocks = (whole + 1 + per_block - 1) / per_block;
  const double Ly = walls ? box_.length[1] : 0.0;
  for (std::size_t c0 = 0; c0 < cuts; c0 += rng::batch) {
    constexpr std::size_t B = rng::batch;
    const std::size_t m = std::min(B, cuts - c0);
    std::uint64_t key[B], ids[B];
    std::uint32_t w[4][B];
    alignas(64) double R2[B], Y[B], cx[B], cy[B], cz[B], last[B];
    alignas(64) double kept[B] = {}, s1[3][B] = {}, s2[6][B] = {};
    for (std::size_t j = 0; j < B; ++j) {
      const CutCell &cut = cut_[c0 + std::min(j, m - 1)]; // padded lanes: tries = 0 below
      const double R = c.radius[cut.row];
      key[j] = cut.key;
      R2[j] = R * R;
      Y[j] = c.x[1][cut.row];
      cx[j] = cut.corner[0];
      cy[j] = cut.corner[1];
      cz[j] = cut.corner[2];
      last[j] = j < m ? whole : 0; // a cell's tries: t < last
    }
    if (fraction > 0.0) {
      for (std::size_t j = 0; j < B; ++j)
        ids[j] = key[j] + 255;
      rng::draw_batch(params_.seed, rng::Purpose::ghost_position, step, ids, w);
      for (std::size_t j = 0; j < m; ++j)
        if (rng::open01(w[0][j]) < fraction)
          last[j] += 1.0;
    }
    for (int b = 0; b < blocks; ++b) {
      for (std::size_t j = 0; j < B; ++j)
        ids[j] = key[j] + static_cast<std::uint64_t>(b * per_block);
      rng::draw_batch(params_.seed, rng::Purpose::ghost_position, step, ids, w);
      if (dim_ == 2) {
        const double even = 2.0 * b, odd = 2.0 * b + 1.0;
        for (std::size_t j = 0; j < B; ++j) {
          const double q[4] = {rng::open01(w[0][j]), rng::open01(w[1][j]), rng::open01(w[2][j]),
                               rng::open01(w[3][j])};
          for (int h = 0; h < 2; ++h) { // the block's tries 2b and 2b + 1
            const double qx = q[2 * h], qy = q[2 * h + 1];
            const double rx = cx[j] + qx, ry = cy[j] + qy, y = Y[j] + ry;
            // bitwise &, not &&: no branch on the random outcome
            const bool in = ((h ? odd : even) < last[j]) & (rx * rx + ry * ry < R2[j]) &
                            ((!walls) | ((y >= 0.0) & (y <= Ly)));
            const double k = in ? 1.0 : 0.0;
            kept[j] += k;
            s1[0][j] += k * qx;
            s1[1][j] += k * qy;
            s2[0][j] += k * qx * qx;
            s2[1][j] += k * qx * qy;
            s2[3][j] += k * qy * qy;
          }
        }
      } else {
        const double t = b;
        for (std::size_t j = 0; j < B; ++j) {
          const double qx = rng::open01(w[0][j]), qy = rng::open01(w[1][j]),
                       qz = rng::open01(w[2][j]);
          const double rx = cx[j] + qx, ry = cy[j] + qy, rz = cz[j] + qz, y = Y[j] + ry;
          const bool in = (t < last[j]) & (rx * rx + ry * ry + rz * rz < R2[j]) &
                          ((!walls) | ((y >= 0.0) & (y <= Ly)));
          const double k = in ? 1.0 : 0.0;
          kept[j] += k;
          s1[0][j] += k * qx;
          s1[1][j] += k * qy;
          s1[2][j] += k * qz;
          s2[0][j] += k * qx * qx;
          s2[1][j] += k * qx * qy;
          s2[2][j] += k * qx * qz;
          s2[3][j] += k * qy * qy;
          s2[4][j] += k * qy * qz;
          s2[5][j] += k * qz * qz;
        }
      }
    }
    for (std::size_t j = 0; j < m; ++j) {
      if (kept[j] == 0.0)
        continue;
      const CutCell &cut = cut_[c0 + j];
      // Made in place: a group built on the stack and copied in stalled on its own stores.
      mpcd::ParticleGroup &g = grid.groups.emplace_back();
      g.cell = cut.cell;
      const auto count = static_cast<std::uint32_t>(kept[j]);
      g.n = count;
      const int upper[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
      for (int k = 0; k < dim_; ++k) {
        g.r[k] = s1[k][j];
        for (int l = 0; l < dim_; ++l)
          g.rr[3 * k + l] = s2[upper[k][l]][j];
      }
      group_row_.push_back(cut.row);
      group_corner_.push_back(cut.corner);
      group_key_.push_back(cut.key);
      ghosts += count;
    }
  }
  ghost_count_ = ghosts;
  // The groups' Gaussians: (1 + D) D for the thermal velocities eta and as many for the MPC-AT
  // draws xi, four a Philox block, keyed by (colloid id, global cell, block): tries 0-2 for
  // eta, 128-130 for xi; a batch of keys at a time (the last batch padded).
  const int rows = dim_ + 1, per_set = (rows * dim_ + 3) / 4, per_group = 2 * per_set;
  const std::size_t groups = grid.groups.size(), keys = groups * per_group;
  group_normals_.resize(keys * 4);
  std::uint64_t ids[rng::batch];
  double z[4][rng::batch];
  std::size_t group = 0, block = 0; // of key b0 + j (counted on: a division per key cost more)
  for (std::size_t b0 = 0; b0 < keys; b0 += rng::batch) {
    const std::size_t m = std::min(rng::batch, keys - b0);
    for (std::size_t j = 0; j < rng::batch; ++j) {
      if (j >= m) {
        ids[j] = 0;
        continue;
      }
      ids[j] = group_key_[group] +
               (block < static_cast<std::size_t>(per_set) ? block : 128 + block - per_set);
      if (++block == static_cast<std::size_t>(per_group)) {
        block = 0;
        ++group;
      }
    }
    rng::gaussian_batch(params_.seed, rng::Purpose::ghost_velocity, step, ids, 4, z);
    for (std::size_t j = 0; j < m; ++j)
      for (int k = 0; k < 4; ++k)
        group_normals_[(b0 + j) * 4 + k] = z[k][j];
  }
  const double sigma = std::sqrt(params_.kT);
  const int m = dim_ + 1, set = (m * dim_ + 3) / 4 * 4; // normals of one set, block-rounded
  GroupBatch batch;
  for (std::size_t q0 = 0; q0 < groups; q0 += lanes) {
    const std::size_t used = std::min<std::size_t>(lanes, groups - q0);
    for (std::size_t l = 0; l < lanes; ++l) {
      const std::size_t q = q0 + std::min(l, used - 1); // (padded lanes: the last group again)
      const mpcd::ParticleGroup &g = grid.groups[q];
      const std::size_t a = group_row_[q];
      const double *normals = &group_normals_[q * per_group * 4];
      batch.n[l] = g.n;
      for (int k = 0; k < 3; ++k) {
        batch.r[k][l] = g.r[k];
        batch.corner[k][l] = group_corner_[q][k];
        batch.U[k][l] = k < dim_ ? c.v[k][a] : 0.0;
        batch.W[k][l] = c.omega[k][a];
      }
      for (int k = 0; k < 9; ++k)
        batch.rr[k][l] = g.rr[k];
      for (int k = 0; k < m * dim_; ++k) {
        batch.z[0][k][l] = normals[k];
        batch.z[1][k][l] = normals[set + k];
      }
    }
    if (dim_ == 2)
      group_velocities<3>(batch, sigma);
    else
      group_velocities<4>(batch, sigma);
    for (std::size_t l = 0; l < used; ++l) {
      const std::size_t q = q0 + l;
      // The cell sums a few groups on (a cache line each, scattered over the grid).
      if (q + prefetch_ahead < groups)
        __builtin_prefetch(&grid.sums[grid.groups[q + prefetch_ahead].cell], 1);
      mpcd::ParticleGroup &g = grid.groups[q];
      for (int b = 0; b < dim_; ++b) {
        g.v[b] = batch.v[b][l];
        g.xi[b] = batch.xi[b][l];
        for (int k = 0; k < dim_; ++k) {
          g.rv[3 * k + b] = batch.rv[3 * k + b][l];
          g.rxi[3 * k + b] = batch.rxi[3 * k + b][l];
        }
      }
      // Into the cell's sums as binning would put the ghosts (taken out again after the
      // collision by the same fixed-point values).
      mpcd::CellSums &sum = grid.sums[g.cell];
      sum.n += g.n;
      for (int k = 0; k < dim_; ++k)
        sum.p[k] += fixed::from_double(g.v[k]);
    }
  }
}

void NoSlipCoupling::take_back_ghost_particles(mpcd::CellGrid &grid,
                                               mpcd::CollisionScratch &collision,
                                               mpcd::Fluid &fluid, Colloids &c) {
  const ScopedSeconds timed(seconds_);
  const std::size_t groups = grid.groups.size();
  if (collision.group_change.size() != groups)
    throw invariant_error("the collision left the ghost particles' groups without their change");
  if (params_.implicit) {
    const ScopedSeconds stage(stage_seconds_[responses]);
    ghost_responses(grid, collision, fluid);
  }
  Stopwatch solve_watch;
  for (std::size_t q = 0; q < groups; ++q) {
    if (q + prefetch_ahead < groups) // (as in add_ghost_particles)
      __builtin_prefetch(&grid.sums[grid.groups[q + prefetch_ahead].cell], 1);
    const mpcd::ParticleGroup &g = grid.groups[q];
    const mpcd::GroupChange &d = collision.group_change[q];
    const double *r = group_corner_[q].data();
    mpcd::CellSums &sum = grid.sums[g.cell];
    sum.n -= g.n; // out of the cell sums again, exactly as they went in
    for (int k = 0; k < dim_; ++k)
      sum.p[k] -= fixed::from_double(g.v[k]);
    // The angular impulse about the centre: sum (c' + r) x dv = c' x dP + sum r x dv.
    double l[3];
    if (dim_ == 2) {
      l[0] = d.rv[1] - d.rv[3];
    } else {
      l[0] = d.rv[5] - d.rv[7];
      l[1] = d.rv[6] - d.rv[2];
      l[2] = d.rv[1] - d.rv[3];
    }
    add_impulse(group_row_[q], r, d.v.data(), l);
  }
  apply_impulses(c, false);
  stage_seconds_[solve] += solve_watch.seconds();
  if (params_.implicit) {
    const ScopedSeconds stage(stage_seconds_[fluid_shift]);
    shift_cut_cells(grid, collision, fluid);
  }
  grid.groups.clear();
}

// The implicit exchange's response of each colloid to its ghosts in a cut cell
// (ghost_response.hpp), added to the colloid's G; the fluid's per unit dX kept for
// shift_cut_cells.
void NoSlipCoupling::ghost_responses(const mpcd::CellGrid &grid,
                                     const mpcd::CollisionScratch &collision,
                                     const mpcd::Fluid &fluid) {
  const std::size_t groups = grid.groups.size();
  cell_slot_.resize(grid.size(), -1);
  slot_cells_.clear();
  slot_fluid_.clear();
  for (std::size_t q = 0; q < groups; ++q) {
    const std::uint32_t cell = grid.groups[q].cell;
    if (cell_slot_[cell] < 0) {
      cell_slot_[cell] = static_cast<std::int32_t>(slot_cells_.size());
      slot_cells_.push_back(cell);
      slot_fluid_.push_back({0.0, 0.0, 0.0, 0.0});
    }
  }
  // The fluid of each cut cell: count and summed offsets from the corner (in fixed point: the
  // same bits whatever the order of the particles, on any number of ranks).
  slot_fixed_.assign(slot_cells_.size(), {0, 0, 0, 0});
  if (collision.position_stride > 0) {
    // MPC-AT+a summed them already, with the ghosts' from_double(sum r) and n added: taken off
    // again, the same integers as a pass over the fluid gives.
    const auto stride = static_cast<std::size_t>(collision.position_stride);
    const auto offset = static_cast<std::size_t>(collision.position_offset);
    for (std::size_t k = 0; k < slot_cells_.size(); ++k) {
      const std::size_t cell = slot_cells_[k];
      slot_fixed_[k][0] = grid.sums[cell].n;
      for (int a = 0; a < dim_; ++a)
        slot_fixed_[k][1 + a] = collision.cell_fixed[cell * stride + offset + a];
    }
    for (std::size_t q = 0; q < groups; ++q) {
      const mpcd::ParticleGroup &g = grid.groups[q];
      auto &f = slot_fixed_[static_cast<std::size_t>(cell_slot_[g.cell])];
      f[0] -= g.n;
      for (int a = 0; a < dim_; ++a)
        f[1 + a] -= fixed::from_double(g.r[a]);
    }
  } else {
    // A cell's particles lie mostly together (sorted by cell every few steps): a run of them is
    // summed in registers and stored once (integers: the same sums in any order).
    const std::size_t n = fluid.size();
    const double sx = grid.shift[0], sy = grid.shift[1], sz = grid.shift[2];
    std::int32_t run = -1;
    std::int64_t acc[4] = {0, 0, 0, 0};
    const auto flush = [&] {
      if (run >= 0)
        for (int k = 0; k < 4; ++k)
          slot_fixed_[static_cast<std::size_t>(run)][k] += acc[k];
    };
    for (std::size_t i = 0; i < n; ++i) {
      const std::int32_t slot = cell_slot_[fluid.cell[i]];
      if (slot != run) {
        flush();
        run = slot;
        acc[0] = acc[1] = acc[2] = acc[3] = 0;
      }
      acc[0] += 1;
      acc[1] += fixed::from_double(mpcd::in_cell_offset(fluid.x[0][i], sx));
      acc[2] += fixed::from_double(mpcd::in_cell_offset(fluid.x[1][i], sy));
      if (dim_ == 3)
        acc[3] += fixed::from_double(mpcd::in_cell_offset(fluid.x[2][i], sz));
    }
    flush();
  }
  for (std::size_t k = 0; k < slot_cells_.size(); ++k) {
    slot_fluid_[k][0] = static_cast<double>(slot_fixed_[k][0]);
    for (int a = 0; a < 3; ++a)
      slot_fluid_[k][1 + a] = fixed::to_double(slot_fixed_[k][1 + a]);
  }
  slot_total_.assign(slot_cells_.size(), 0.0);
  for (std::size_t k = 0; k < slot_cells_.size(); ++k)
    slot_total_[k] = grid.sums[slot_cells_[k]].n; // ghosts still in
  for (const mpcd::VirtualCell &v : grid.virtual_cells)
    if (cell_slot_[v.cell] >= 0)
      slot_total_[static_cast<std::size_t>(cell_slot_[v.cell])] += v.count;
  // Per group and degree of freedom i of dX, what the fluid's shift needs (du, dw and the
  // momentum rows of column i of G): a few cache lines a group, not GhostResponse's ten.
  // In the plane only du_x, du_y, dw_z, G_x and G_y of each dof are not zero: 5 a dof.
  const std::size_t per = static_cast<std::size_t>(dof_) * (dim_ == 2 ? 5 : 6 + dim_);
  group_fluid_.resize(groups * per); // (each group's entries written below: no fill)
  if (dim_ == 2) {
    planar_responses(grid, collision);
    return;
  }
  for (std::size_t q = 0; q < groups; ++q) {
    const mpcd::ParticleGroup &g = grid.groups[q];
    const mpcd::GroupChange &d = collision.group_change[q];
    const double *corner = group_corner_[q].data();
    const auto slot = static_cast<std::size_t>(cell_slot_[g.cell]);
    const double N = slot_total_[slot];
    if (g.n == 0) {
      std::fill_n(&group_fluid_[q * per], per, 0.0);
      continue;
    }
    GhostResponse out;
    const bool dry = slot_fluid_[slot][0] == 0.0; // only ghosts (and virtual particles) here
    // Moments about the centre: m1 = n c + sum r, m2 = n c c^T + c (sum r)^T + (sum r) c^T +
    // sum r r^T.
    GhostMoments m;
    m.m0 = g.n;
    m.N = N;
    for (int a = 0; a < 3; ++a) {
      m.m1[a] = m.m0 * corner[a] + g.r[a];
      m.rc[a] = corner[a] + d.rc[a];
      for (int b = 0; b < 3; ++b) {
        m.m2[a][b] = m.m0 * corner[a] * corner[b] + corner[a] * g.r[b] + g.r[a] * corner[b] +
                     g.rr[3 * a + b];
        m.Q[a][b] = d.response[3 * a + b];
        m.spin[a][b] = d.spin[3 * a + b];
      }
    }
    ghost_response_3d(m, out); // (the plane went to planar_responses)
    // A cell without fluid: the ghosts still mix among themselves (the colloid's spin relative
    // to its ghosts' mean is damped, and thermal noise enters: the angular rows stay), but
    // momentum has no fluid to go to: of one colloid's ghosts alone it is conserved anyway; of
    // two colloids' or with a wall's virtual particles the response is left out.
    if (dry) {
      for (int k = 0; k < dim_; ++k)
        for (int i = 0; i < dof_; ++i)
          out.G[k][i] = 0.0;
      for (int i = 0; i < dof_; ++i)
        for (int a = 0; a < 3; ++a)
          out.du[i][a] = out.dw[i][a] = 0.0;
    }
    add_G(group_row_[q], out.G);
    double *f = &group_fluid_[q * per];
    for (int i = 0; i < dof_; ++i, f += 6 + dim_)
      for (int a = 0; a < 3; ++a) {
        f[a] = out.du[i][a];
        f[3 + a] = out.dw[i][a];
        if (a < dim_)
          f[6 + a] = out.G[a][i];
      }
  }
}

// ghost_responses in the plane: the same numbers from the moments the planar response reads,
// and the five non-zero entries of each dof into group_fluid_.
void NoSlipCoupling::planar_responses(const mpcd::CellGrid &grid,
                                      const mpcd::CollisionScratch &collision) {
  const std::size_t groups = grid.groups.size();
  constexpr std::size_t per = 15; // 3 dof x 5
  for (std::size_t q = 0; q < groups; ++q) {
    const mpcd::ParticleGroup &g = grid.groups[q];
    const mpcd::GroupChange &d = collision.group_change[q];
    const double *corner = group_corner_[q].data();
    const auto slot = static_cast<std::size_t>(cell_slot_[g.cell]);
    double *f = &group_fluid_[q * per];
    if (g.n == 0) {
      std::fill_n(f, per, 0.0);
      continue;
    }
    // (as GhostMoments is filled in ghost_responses: the same expressions)
    PlanarMoments m;
    m.m0 = g.n;
    m.N = slot_total_[slot];
    m.spin = d.spin[8];
    const double cx = corner[0], cy = corner[1];
    m.m1x = std::fma(m.m0, cx, g.r[0]); // (fused there, and here however the products are shared)
    m.m1y = std::fma(m.m0, cy, g.r[1]);
    m.rcx = cx + d.rc[0];
    m.rcy = cy + d.rc[1];
    m.m2xx = m.m0 * cx * cx + cx * g.r[0] + g.r[0] * cx + g.rr[0];
    m.m2xy = m.m0 * cx * cy + cx * g.r[1] + g.r[0] * cy + g.rr[1];
    m.m2yy = m.m0 * cy * cy + cy * g.r[1] + g.r[1] * cy + g.rr[4];
    m.Qxx = d.response[0];
    m.Qxy = d.response[1];
    m.Qyx = d.response[3];
    m.Qyy = d.response[4];
    PlanarResponse out;
    planar_response(m, out);
    if (slot_fluid_[slot][0] == 0.0) { // dry: as in ghost_responses
      for (int k = 0; k < 2; ++k)
        for (int i = 0; i < 3; ++i)
          out.G[k][i] = 0.0;
      for (int i = 0; i < 3; ++i)
        out.du[i][0] = out.du[i][1] = out.dw[i] = 0.0;
    }
    std::int64_t *G = &impulse_[group_row_[q] * static_cast<std::size_t>(stride_) + 3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        G[i * 3 + j] += fixed::from_double(out.G[i][j]);
    for (int i = 0; i < 3; ++i, f += 5) {
      f[0] = out.du[i][0];
      f[1] = out.du[i][1];
      f[2] = out.dw[i];
      f[3] = out.G[0][i];
      f[4] = out.G[1][i];
    }
  }
}

// The fluid's share of the implicit exchange: each cut cell's particles get, for each group
// there, Q du + dw x (r - rc) at the colloid's dX/2; and, spread evenly, whatever momentum the
// colloids' G dX/2 has beyond that (other colloids' ghosts and a wall's virtual particles in
// the cell take a share of the response that is not followed), so that momentum is conserved
// exactly.
void NoSlipCoupling::shift_cut_cells(const mpcd::CellGrid &grid, mpcd::CollisionScratch &collision,
                                     mpcd::Fluid &fluid) {
  const std::size_t slots = slot_cells_.size();
  slot_rc_.assign(slots, {0.0, 0.0, 0.0});
  // Summed over the groups of a cell in fixed point (their order depends on the colloid rows').
  slot_sums_.assign(slots, {});
  const std::size_t per = static_cast<std::size_t>(dof_) * (dim_ == 2 ? 5 : 6 + dim_);
  for (std::size_t q = 0; q < grid.groups.size() && dim_ == 2; ++q) {
    // The plane's five entries a dof (planar_responses); the sums that stay zero are left out.
    const auto slot = static_cast<std::size_t>(cell_slot_[grid.groups[q].cell]);
    const double *g = &group_fluid_[q * per];
    const double *h = &half_[group_row_[q] * 3];
    auto &sum = slot_sums_[slot];
    double dux = 0.0, duy = 0.0, dw = 0.0, px = 0.0, py = 0.0;
    for (int i = 0; i < 3; ++i, g += 5) {
      dux += g[0] * h[i];
      duy += g[1] * h[i];
      dw += g[2] * h[i];
      px += g[3] * h[i];
      py += g[4] * h[i];
    }
    sum[0] += fixed::from_double(dux);
    sum[1] += fixed::from_double(duy);
    sum[5] += fixed::from_double(dw);
    sum[6] += fixed::from_double(px);
    sum[7] += fixed::from_double(py);
    slot_rc_[slot] = collision.group_change[q].rc; // the cell's, from its corner
  }
  for (std::size_t q = 0; q < grid.groups.size() && dim_ == 3; ++q) {
    const auto slot = static_cast<std::size_t>(cell_slot_[grid.groups[q].cell]);
    const double *g = &group_fluid_[q * per];
    const double *h = &half_[group_row_[q] * dof_];
    auto &sum = slot_sums_[slot];
    for (int a = 0; a < 3; ++a) {
      double du = 0.0, dw = 0.0, p = 0.0;
      for (int i = 0; i < dof_; ++i) {
        const double *gi = g + i * (6 + dim_);
        du += gi[a] * h[i];
        dw += gi[3 + a] * h[i];
        if (a < dim_)
          p += gi[6 + a] * h[i];
      }
      sum[a] += fixed::from_double(du);
      sum[3 + a] += fixed::from_double(dw);
      sum[6 + a] += fixed::from_double(p);
    }
    slot_rc_[slot] = collision.group_change[q].rc; // the cell's, from its corner
  }
  // Per slot the fluid's velocity change as v += c + w x r (r from the cell's corner):
  // c = shift + residual - w x rc, the residual spreading evenly whatever momentum the colloids'
  // G dX/2 has beyond the fluid's response n shift + w x (sum r - n rc).
  slot_motion_.resize(slots);
  for (std::size_t k = 0; k < slots; ++k) {
    double shift[3], w[3], residual[3], rc[3] = {0.0, 0.0, 0.0}, wrc[3];
    for (int a = 0; a < 3; ++a) {
      shift[a] = fixed::to_double(slot_sums_[k][a]);
      w[a] = fixed::to_double(slot_sums_[k][3 + a]);
      residual[a] = 0.0;
    }
    for (int a = 0; a < dim_; ++a)
      rc[a] = slot_rc_[k][a];
    const auto &f = slot_fluid_[k];
    if (f[0] > 0.0) {
      double off[3] = {0.0, 0.0, 0.0}, wr[3];
      for (int a = 0; a < dim_; ++a)
        off[a] = f[1 + a] - f[0] * rc[a];
      cross(w, off, wr);
      for (int a = 0; a < dim_; ++a)
        residual[a] = (fixed::to_double(slot_sums_[k][6 + a]) - (f[0] * shift[a] + wr[a])) / f[0];
    }
    cross(w, rc, wrc);
    auto &m = slot_motion_[k];
    for (int a = 0; a < 3; ++a) {
      m[a] = shift[a] + residual[a] - wrc[a];
      m[3 + a] = w[a];
    }
  }
  if (collision.shift_stride > 0) {
    // MPC-AT+a has collided the cells, not yet the particles: each cut cell's change goes into
    // its record, and the particle pass adds it to the new velocities as shift_cut_cells_fluid
    // would, with the same operations (one pass over the fluid, not two).
    const auto stride = static_cast<std::size_t>(collision.shift_stride);
    const auto offset = static_cast<std::size_t>(collision.shift_offset);
    for (std::size_t k = 0; k < slots; ++k) {
      double *par = &collision.cell[slot_cells_[k] * stride + offset];
      const auto &m = slot_motion_[k];
      if (dim_ == 2) {
        par[0] = m[0];
        par[1] = m[1];
        par[2] = m[5];
      } else {
        for (int a = 0; a < 6; ++a)
          par[a] = m[a];
      }
    }
    collision.cells_shifted = true;
  } else {
    shift_cut_cells_fluid(grid, fluid);
  }
  for (const std::uint32_t cell : slot_cells_)
    cell_slot_[cell] = -1;
}

// The pass over the fluid: each particle of a cut cell gets its slot's c + w x r.
void NoSlipCoupling::shift_cut_cells_fluid(const mpcd::CellGrid &grid, mpcd::Fluid &fluid) {
  const std::size_t n = fluid.size();
  const double sx = grid.shift[0], sy = grid.shift[1], sz = grid.shift[2];
  if (dim_ == 2) {
    // A block at a time: first which particles lie in a cut cell, without a branch (about half
    // of them, at random: a branch missed often), then those particles.
    constexpr std::size_t block = 512;
    std::uint32_t at[block];
    std::int32_t slot_of[block];
    for (std::size_t i0 = 0; i0 < n; i0 += block) {
      const std::size_t m = std::min(block, n - i0);
      std::size_t k = 0;
      for (std::size_t j = 0; j < m; ++j) {
        const std::int32_t slot = cell_slot_[fluid.cell[i0 + j]];
        at[k] = static_cast<std::uint32_t>(j);
        slot_of[k] = slot;
        k += slot >= 0;
      }
      for (std::size_t q = 0; q < k; ++q) {
        const std::size_t i = i0 + at[q];
        const double *m = slot_motion_[static_cast<std::size_t>(slot_of[q])].data();
        const double rx = mpcd::in_cell_offset(fluid.x[0][i], sx);
        const double ry = mpcd::in_cell_offset(fluid.x[1][i], sy);
        fluid.v[0][i] += m[0] - m[5] * ry;
        fluid.v[1][i] += m[1] + m[5] * rx;
      }
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      const std::int32_t slot = cell_slot_[fluid.cell[i]];
      if (slot < 0)
        continue;
      const double *m = slot_motion_[static_cast<std::size_t>(slot)].data();
      const double r[3] = {mpcd::in_cell_offset(fluid.x[0][i], sx),
                           mpcd::in_cell_offset(fluid.x[1][i], sy),
                           mpcd::in_cell_offset(fluid.x[2][i], sz)};
      double wr[3];
      cross(m + 3, r, wr);
      for (int a = 0; a < 3; ++a)
        fluid.v[a][i] += m[a] + wr[a];
    }
  }
}

} // namespace narrows::coupling
