// Stochastic rotation dynamics (seed 000 eq 3.4-3.8).
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/mpcd/collision.hpp"

#include <cmath>
#include <numbers>

namespace narrows::mpcd {

namespace {

// Per-cell parameters: 2D {ux, uy, cos, +-sin}; 3D {ux, uy, uz, R (row-major 3x3)}.
template <int D> constexpr int stride = D == 2 ? 4 : 12;

// The rotation of one cell: 2D {cos, +-sin}; 3D the row-major matrix, about a random axis.
template <int D>
void set_rotation(double *rot, double ca, double sa, std::uint64_t seed, std::uint64_t step,
                  std::uint64_t cell_id) {
  const auto r = rng::draw(seed, rng::Purpose::srd_rotation, step, cell_id);
  if constexpr (D == 2) {
    rot[0] = ca;
    rot[1] = (r[0] & 1u) ? sa : -sa;
  } else {
    // Random unit axis uniform on the sphere (seed 000 eq 3.8), Rodrigues' rotation matrix.
    const double cos_t = 2.0 * rng::open01(r[0]) - 1.0;
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    const double ph = 2.0 * std::numbers::pi * rng::open01(r[1]);
    const double ax = sin_t * std::cos(ph), ay = sin_t * std::sin(ph), az = cos_t;
    const double oc = 1.0 - ca;
    double *R = rot;
    R[0] = ca + ax * ax * oc;
    R[1] = ax * ay * oc - az * sa;
    R[2] = ax * az * oc + ay * sa;
    R[3] = ay * ax * oc + az * sa;
    R[4] = ca + ay * ay * oc;
    R[5] = ay * az * oc - ax * sa;
    R[6] = az * ax * oc - ay * sa;
    R[7] = az * ay * oc + ax * sa;
    R[8] = ca + az * az * oc;
  }
}

template <int D>
void srd_cells(const CellGrid &g, std::vector<double> &par, double angle, std::uint64_t seed,
               std::uint64_t step) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  const std::size_t nc = g.size();
  par.resize(nc * stride<D>);
  for (std::size_t c = 0; c < nc; ++c) {
    const CellSums &s = g.sums[c];
    double *p = &par[c * stride<D>];
    const double inv_n = s.n ? 1.0 / s.n : 0.0;
    for (int k = 0; k < D; ++k)
      p[k] = fixed::to_double(s.p[k]) * inv_n;
    if (s.n < 2) { // nothing to mix: the identity
      if constexpr (D == 2) {
        p[2] = 1.0;
        p[3] = 0.0;
      } else {
        for (int k = 0; k < 9; ++k)
          p[3 + k] = (k % 4 == 0) ? 1.0 : 0.0;
      }
      continue;
    }
    set_rotation<D>(p + D, ca, sa, seed, step, g.global_id(c));
  }
  // Cells cut by a wall: the mean velocity includes the virtual particles (000 eq 3.14), and
  // a lone real particle is mixed with them too.
  for (const VirtualCell &v : g.virtual_cells) {
    const CellSums &s = g.sums[v.cell];
    if (s.n == 0)
      continue;
    double *p = &par[v.cell * stride<D>];
    const double inv_n = 1.0 / (s.n + v.count);
    for (int k = 0; k < D; ++k)
      p[k] = (fixed::to_double(s.p[k]) + v.momentum[k]) * inv_n;
    if (s.n == 1)
      set_rotation<D>(p + D, ca, sa, seed, step, g.global_id(v.cell));
  }
}

template <int D> void srd_particles(Fluid &f, const std::vector<double> &par) {
  double *vx = f.v[0].data(), *vy = f.v[1].data(), *vz = f.v[2].data();
  const std::uint32_t *cell = f.cell.data();
  const std::size_t n = f.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double *p = &par[static_cast<std::size_t>(cell[i]) * stride<D>];
    if constexpr (D == 2) {
      const double wx = vx[i] - p[0], wy = vy[i] - p[1];
      vx[i] = p[0] + p[2] * wx - p[3] * wy;
      vy[i] = p[1] + p[3] * wx + p[2] * wy;
    } else {
      const double wx = vx[i] - p[0], wy = vy[i] - p[1], wz = vz[i] - p[2];
      const double *R = p + 3;
      vx[i] = p[0] + R[0] * wx + R[1] * wy + R[2] * wz;
      vy[i] = p[1] + R[3] * wx + R[4] * wy + R[5] * wz;
      vz[i] = p[2] + R[6] * wx + R[7] * wy + R[8] * wz;
    }
  }
}

} // namespace

void collide_srd(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double angle_rad,
                 std::uint64_t seed, std::uint64_t step) {
  if (grid.dim == 3) {
    srd_cells<3>(grid, scratch.cell, angle_rad, seed, step);
    srd_particles<3>(fluid, scratch.cell);
  } else {
    srd_cells<2>(grid, scratch.cell, angle_rad, seed, step);
    srd_particles<2>(fluid, scratch.cell);
  }
}

} // namespace narrows::mpcd
