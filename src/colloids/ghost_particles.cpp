// Ghost particles inside no-slip colloids for the collision step (seed 001 §4.2.1, eq 4.18).
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/no_slip.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/core/rng_batch.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/mpcd/streaming.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace narrows::colloids {

namespace {

// The key of a ghost particle's draws: colloid id, global cell, try (255: the fractional try).
std::uint64_t ghost_key(std::uint64_t colloid, std::uint64_t cell, std::uint64_t t) {
  return (colloid << 40) | (cell << 8) | t;
}

} // namespace

void NoSlipCoupling::add_ghost_particles(mpcd::Fluid &fluid, mpcd::CellGrid &grid,
                                         const Colloids &c, std::uint64_t step) {
  const ScopedSeconds timed(seconds_);
  first_ghost_ = fluid.size();
  ghost_row_.clear();
  const double n = params_.density, sigma = std::sqrt(params_.kT);
  const int whole = static_cast<int>(std::floor(n));
  const double fraction = n - whole;
  const int NX = grid.global_columns, nx = grid.cells[0], ny = grid.cells[1], nz = grid.cells[2];
  const bool walls = grid.walls_y;
  const double *sh = grid.shift.data();
  const int per_block = dim_ == 2 ? 2 : 1;
  // Fills position_words_ with the blocks of a cell's tries and its fractional try.
  const auto position_keys = [&](std::uint64_t colloid, std::uint64_t gcell, int blocks) {
    const std::size_t count = static_cast<std::size_t>(blocks) + 1;
    position_words_.resize(count);
    std::uint64_t ids[rng::batch];
    std::uint32_t w[4][rng::batch];
    for (std::size_t b0 = 0; b0 < count; b0 += rng::batch) {
      const std::size_t m = std::min(rng::batch, count - b0);
      for (std::size_t j = 0; j < rng::batch; ++j) {
        const std::size_t b = b0 + j;
        ids[j] = j >= m ? 0
                 : b + 1 == count
                     ? ghost_key(colloid, gcell, 255)
                     : ghost_key(colloid, gcell, b * static_cast<std::size_t>(per_block));
      }
      rng::draw_batch(params_.seed, rng::Purpose::ghost_position, step, ids, w);
      for (std::size_t j = 0; j < m; ++j)
        position_words_[b0 + j] = {w[0][j], w[1][j], w[2][j], w[3][j]};
    }
  };
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
    for (int i = lo[0]; i <= hi[0]; ++i) {
      const int column = ((i % NX) + NX) % NX;
      const int ix = column - grid.first_column;
      if (ix < 0 || ix >= nx)
        continue;
      for (int j = lo[1]; j <= hi[1]; ++j) {
        const int row = walls ? j : ((j % ny) + ny) % ny;
        for (int l = lo[2]; l <= hi[2]; ++l) {
          const int layer = dim_ == 3 ? ((l % nz) + nz) % nz : 0;
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
          if (near2 >= R2 || far2 <= R2)
            continue;
          const std::size_t cell =
              ix + static_cast<std::size_t>(nx) * (row + static_cast<std::size_t>(ny) * layer);
          const std::uint64_t gcell = grid.global_id(cell);
          // The blocks of the cell's tries (one block places two tries in 2D, words 0-1 and
          // 2-3, one in 3D; keyed by the first try of the block) and, last, that of the
          // fractional try (255), all in batches: bitwise rng::draw's.
          const int blocks = (whole + 1 + per_block - 1) / per_block;
          position_keys(c.id[a], gcell, blocks);
          int tries = whole;
          if (fraction > 0.0 && rng::open01(position_words_[blocks][0]) < fraction)
            ++tries;
          for (int t = 0; t < tries; ++t) {
            const std::uint64_t key = ghost_key(c.id[a], gcell, static_cast<std::uint64_t>(t));
            const int word = dim_ == 2 ? 2 * (t & 1) : 0;
            const auto &u = position_words_[t / per_block];
            double r[3] = {0.0, 0.0, 0.0}, r2 = 0.0;
            for (int k = 0; k < dim_; ++k) {
              r[k] = corner[k] + rng::open01(u[word + k]);
              r2 += r[k] * r[k];
            }
            if (r2 >= R2)
              continue;
            const double y = X[1] + r[1];
            if (walls && !(y >= 0.0 && y <= box_.length[1]))
              continue;
            const double w[3] = {c.omega[0][a], c.omega[1][a], c.omega[2][a]};
            const double rigid[3] = {c.v[0][a] + w[1] * r[2] - w[2] * r[1],
                                     c.v[1][a] + w[2] * r[0] - w[0] * r[2],
                                     (dim_ == 3 ? c.v[2][a] : 0.0) + w[0] * r[1] - w[1] * r[0]};
            // The position from the cell's own corner, so that binning finds this cell.
            const double origin[3] = {column + sh[0], (walls ? j - 1 : row) + sh[1],
                                      dim_ == 3 ? layer + sh[2] : 0.0};
            for (int k = 0; k < dim_; ++k) {
              double x = origin[k] + rng::open01(u[word + k]);
              if (!(k == 1 && walls))
                x = mpcd::wrap_periodic(x, box_.length[k]);
              fluid.x[k].push_back(x);
              fluid.v[k].push_back(rigid[k]); // + the thermal part, drawn below in batches
            }
            fluid.id.push_back(ghost_particle_id | key);
            fluid.cell.push_back(0); // binned below
            ghost_row_.push_back(static_cast<std::uint32_t>(a));
          }
        }
      }
    }
  }
  // The ghosts' Maxwell velocities at kT, keyed by (colloid id, global cell, try): a batch of
  // keys at a time (the vectorised Philox and Box-Muller of rng_batch; the last batch padded).
  const std::size_t made = fluid.size() - first_ghost_;
  std::uint64_t keys[rng::batch];
  double g[4][rng::batch];
  for (std::size_t b0 = 0; b0 < made; b0 += rng::batch) {
    const std::size_t m = std::min(rng::batch, made - b0);
    for (std::size_t j = 0; j < rng::batch; ++j)
      keys[j] = j < m ? fluid.id[first_ghost_ + b0 + j] & ~ghost_particle_id : 0;
    rng::gaussian_batch(params_.seed, rng::Purpose::ghost_velocity, step, keys, dim_ == 2 ? 2 : 4,
                        g);
    for (int k = 0; k < dim_; ++k) {
      double *v = fluid.v[k].data() + first_ghost_ + b0;
      for (std::size_t j = 0; j < m; ++j)
        v[j] += sigma * g[k][j];
    }
  }
  for (int k = 0; k < dim_; ++k)
    ghost_v0_[k].assign(fluid.v[k].begin() + static_cast<std::ptrdiff_t>(first_ghost_),
                        fluid.v[k].end());
  mpcd::bin_more_particles(fluid, grid, first_ghost_);
}

void NoSlipCoupling::take_back_ghost_particles(mpcd::Fluid &fluid, mpcd::CellGrid &grid,
                                               Colloids &c) {
  const ScopedSeconds timed(seconds_);
  const std::size_t m = ghost_row_.size();
  for (std::size_t g = 0; g < m; ++g) {
    const std::size_t i = first_ghost_ + g, a = ghost_row_[g];
    double dp[3] = {0.0, 0.0, 0.0}, r[3] = {0.0, 0.0, 0.0};
    mpcd::CellSums &sum = grid.sums[fluid.cell[i]];
    sum.n -= 1; // out of the cell sums again, exactly as binning put it in
    for (int k = 0; k < dim_; ++k) {
      dp[k] = fluid.v[k][i] - ghost_v0_[k][g];
      sum.p[k] -= fixed::from_double(ghost_v0_[k][g]);
      r[k] = fluid.x[k][i] - c.x[k][a];
      if (!(k == 1 && box_.walls_y))
        r[k] = minimum_image(r[k], box_.length[k]);
    }
    add_impulse(a, r, dp);
  }
  fluid.resize(first_ghost_);
  apply_impulses(c, false);
}

} // namespace narrows::colloids
