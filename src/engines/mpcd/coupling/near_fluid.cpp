// Choosing the fluid particles of the MD sub-steps from a cell list of the fluid.
#include "narrows/engines/mpcd/coupling/near_fluid.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/potentials.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::coupling {

using namespace narrows::colloids;

namespace {

// The largest path |v| dt + a dt^2 / 2 of particle i.
template <int D> double reach(const mpcd::Fluid &f, std::size_t i, double dt, double half_a_dt2) {
  double v2 = 0.0;
  for (int k = 0; k < D; ++k)
    v2 += f.v[k][i] * f.v[k][i];
  return std::sqrt(v2) * dt + half_a_dt2;
}

template <int D, bool WallsY>
void select(const CellList &cl, const mpcd::Fluid &f, const Colloids &c, const mpcd::Box &box,
            const std::vector<double> &margin, double dt, double fluid_accel, double max_reach,
            std::vector<std::uint8_t> &flag, std::vector<std::uint32_t> &index) {
  const std::size_t n = f.size();
  const auto &cells = cl.cells;
  const double half_a_dt2 = 0.5 * fluid_accel * dt * dt;
  const double *X[3] = {f.x[0].data(), f.x[1].data(), D == 3 ? f.x[2].data() : nullptr};
  flag.assign(n, 0);
  index.clear();
  const auto &L = box.length;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double range = repulsive_cutoff(6, c.radius[a]) + margin[a];
    const double xc[3] = {c.x[0][a], c.x[1][a], D == 3 ? c.x[2][a] : 0.0};
    // Cells along each axis within range + max_reach of the colloid's cell (all if that covers
    // the axis); along a wall axis clipped at the ends.
    std::array<std::vector<int>, 3> axis;
    for (int k = 0; k < D; ++k) {
      const int nk = cells[k];
      const int home = mpcd::clamped_cell(c.x[k][a], cl.inv_cell[k], nk, "colloid", c.id[a], k);
      const int w = static_cast<int>(std::ceil((range + max_reach) * cl.inv_cell[k]));
      if (2 * w + 1 >= nk) {
        for (int q = 0; q < nk; ++q)
          axis[k].push_back(q);
      } else if (WallsY && k == 1) {
        for (int q = std::max(0, home - w); q <= std::min(nk - 1, home + w); ++q)
          axis[k].push_back(q);
      } else {
        for (int q = home - w; q <= home + w; ++q)
          axis[k].push_back(q < 0 ? q + nk : (q >= nk ? q - nk : q));
      }
    }
    if constexpr (D == 2)
      axis[2] = {0};
    for (const int cz : axis[2])
      for (const int cy : axis[1])
        for (const int cx : axis[0]) {
          const std::size_t cell =
              (static_cast<std::size_t>(cz) * cells[1] + static_cast<std::size_t>(cy)) * cells[0] +
              static_cast<std::size_t>(cx);
          for (std::int32_t j = cl.head[cell]; j >= 0; j = cl.next[j]) {
            const auto js = static_cast<std::size_t>(j);
            if (flag[js])
              continue;
            const double xj[3] = {X[0][js], X[1][js], D == 3 ? X[2][js] : 0.0};
            double d[3];
            const double r2 = separation<D, WallsY>(xj, xc, L, d);
            const double limit = range + reach<D>(f, js, dt, half_a_dt2);
            if (r2 < limit * limit) {
              flag[js] = 1;
              index.push_back(static_cast<std::uint32_t>(j));
            }
          }
        }
  }
}

} // namespace

double fluid_reach(const mpcd::Fluid &f, double dt, double fluid_accel, double v2_known) {
  if (v2_known >= 0.0) // (a relative 1e-12 more: its sums may round the other way than below)
    return f.size() == 0 ? 0.0
                         : std::sqrt(v2_known) * (1.0 + 1e-12) * dt + 0.5 * fluid_accel * dt * dt;
  // The largest |v|^2, then one square root: the same number as the largest |v| dt + a dt^2/2
  // (sqrt and the affine map are monotonic and correctly rounded), at a third of the cost.
  // Eight running maxima (the maximum does not depend on the order: the compiler may keep
  // them in one vector register), then the largest of them.
  constexpr std::size_t lanes = 8;
  double most[lanes] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const std::size_t n = f.size();
  const double *vx = f.v[0].data(), *vy = f.v[1].data(), *vz = f.v[2].data();
  if (f.dim == 3) {
    for (std::size_t i = 0; i < n; ++i)
      most[i % lanes] = std::max(most[i % lanes], vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
  } else {
    for (std::size_t i = 0; i < n; ++i)
      most[i % lanes] = std::max(most[i % lanes], vx[i] * vx[i] + vy[i] * vy[i]);
  }
  double v2_max = 0.0;
  for (const double m : most)
    v2_max = std::max(v2_max, m);
  return n == 0 ? 0.0 : std::sqrt(v2_max) * dt + 0.5 * fluid_accel * dt * dt;
}

void select_near_fluid(const CellList &cells, const mpcd::Fluid &f, const Colloids &c,
                       const mpcd::Box &box, const std::vector<double> &margin, double dt,
                       double fluid_accel, double max_reach, std::vector<std::uint8_t> &flag,
                       std::vector<std::uint32_t> &index) {
  if (box.dim == 3)
    box.walls_y
        ? select<3, true>(cells, f, c, box, margin, dt, fluid_accel, max_reach, flag, index)
        : select<3, false>(cells, f, c, box, margin, dt, fluid_accel, max_reach, flag, index);
  else
    box.walls_y
        ? select<2, true>(cells, f, c, box, margin, dt, fluid_accel, max_reach, flag, index)
        : select<2, false>(cells, f, c, box, margin, dt, fluid_accel, max_reach, flag, index);
}

} // namespace narrows::coupling
