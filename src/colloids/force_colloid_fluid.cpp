// Colloid-fluid WCA forces (Tabatabaei (2008) eq 3.42) from a cell list of the fluid.
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::colloids {

template <int D, bool WallsY>
double add_colloid_fluid_wca(const CellList &cl, const mpcd::Fluid &f, const Colloids &c,
                             const mpcd::Box &box, double eps, bool want_energy,
                             FluidForces &on_fluid, std::vector<std::int64_t> &on_colloids) {
  // Each colloid scans the cells within one cell of its own (all cells of an axis with fewer
  // than three, so none is visited twice).
  const auto &L = box.length;
  const auto &cells = cl.cells;
  const double *X[3] = {f.x[0].data(), f.x[1].data(), D == 3 ? f.x[2].data() : nullptr};
  double energy = 0.0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double cut2 = std::pow(repulsive_cutoff(6, c.radius[a]), 2);
    const double s2cf = c.radius[a] * c.radius[a];
    double xc[3] = {0.0, 0.0, 0.0};
    int lo[3], hi[3], home[3];
    for (int k = 0; k < D; ++k) {
      xc[k] = c.x[k][a];
      home[k] = mpcd::clamped_cell(xc[k], cl.inv_cell[k], cells[k], "colloid", c.id[a], k);
      const bool periodic = !(WallsY && k == 1);
      if (cells[k] < 3) {
        lo[k] = 0, hi[k] = cells[k] - 1, home[k] = 0;
      } else if (periodic) {
        lo[k] = -1, hi[k] = 1;
      } else {
        lo[k] = home[k] > 0 ? -1 : 0, hi[k] = home[k] < cells[k] - 1 ? 1 : 0;
      }
    }
    int off[3] = {0, 0, 0};
    for (off[2] = D == 3 ? lo[2] : 0; off[2] <= (D == 3 ? hi[2] : 0); ++off[2])
      for (off[1] = lo[1]; off[1] <= hi[1]; ++off[1])
        for (off[0] = lo[0]; off[0] <= hi[0]; ++off[0]) {
          std::size_t cell = 0;
          for (int k = D - 1; k >= 0; --k) {
            int ck = home[k] + off[k];
            ck = ck < 0 ? ck + cells[k] : (ck >= cells[k] ? ck - cells[k] : ck);
            cell = cell * static_cast<std::size_t>(cells[k]) + static_cast<std::size_t>(ck);
          }
          for (std::int32_t j = cl.head[cell]; j >= 0; j = cl.next[j]) {
            const double xj[3] = {X[0][j], X[1][j], D == 3 ? X[2][j] : 0.0};
            double d[3];
            const double r2 = separation<D, WallsY>(xj, xc, L, d);
            if (r2 >= cut2)
              continue;
            const PairTerm t = repulsive_pair<6>(r2, s2cf, eps);
            if (want_energy)
              energy += t.energy;
            const auto js = static_cast<std::size_t>(j);
            if (!on_fluid.flag[js]) {
              on_fluid.flag[js] = 1;
              on_fluid.touched.push_back(static_cast<std::uint32_t>(j));
            }
            for (int k = 0; k < D; ++k) {
              const std::int64_t q = to_fixed(t.f_over_r * d[k]);
              on_fluid.value[js * D + k] += q;
              on_colloids[a * D + k] -= q;
            }
          }
        }
  }
  return energy;
}

#define NARROWS_INSTANTIATE(D, W)                                                                  \
  template double add_colloid_fluid_wca<D, W>(const CellList &, const mpcd::Fluid &,               \
                                              const Colloids &, const mpcd::Box &, double, bool,   \
                                              FluidForces &, std::vector<std::int64_t> &);
NARROWS_FOR_EACH_DIM_AND_WALLS(NARROWS_INSTANTIATE)
#undef NARROWS_INSTANTIATE

} // namespace narrows::colloids
