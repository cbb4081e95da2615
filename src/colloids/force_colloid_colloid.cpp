// Colloid-colloid 48-24 forces (seed 000 eq 3.43) from a cell list of the colloids.
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/mpcd/cell_grid.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::colloids {

template <int D, bool WallsY>
double add_colloid_colloid_4824(CellList &cl, std::vector<int> &cell_of,
                                std::vector<std::uint32_t> &partners, const Colloids &c,
                                std::size_t owned, const mpcd::Box &box, double eps,
                                bool want_energy, std::vector<std::int64_t> &on_colloids) {
  // Colloid a meets the partners b > a in the cells within one of its own (along an axis of
  // fewer than three cells, all of its cells, so no cell is visited twice and no pair counted
  // twice; along a wall axis the range stops at the walls). The pair forces are rounded to
  // fixed point and summed as integers, so the order of the pairs does not matter; the energy
  // is a sum of doubles, so for it the partners of each a are taken in increasing b, the order
  // of a double loop over a < b.
  // Rows from `owned` on are ghost copies (ghosts.hpp): a pair adds only to its owned rows (the
  // owner of the other side adds its half from the same positions, bitwise the negative), pairs
  // of two ghosts are left to their owners, and the energy of a pair with a ghost is counted
  // on the rank that owns the colloid with the smaller id.
  const std::size_t nc = c.size();
  const auto &L = box.length;
  const auto &cells = cl.cells;
  cl.clear();
  cl.next.resize(nc);
  cell_of.resize(nc * D);
  for (std::size_t a = 0; a < nc; ++a) {
    std::size_t cell = 0;
    for (int k = D - 1; k >= 0; --k) {
      const int n = cells[k];
      const int ck = mpcd::clamped_cell(c.x[k][a], cl.inv_cell[k], n, "colloid", c.id[a], k);
      cell_of[a * D + k] = ck;
      cell = cell * static_cast<std::size_t>(n) + static_cast<std::size_t>(ck);
    }
    cl.push(cell, static_cast<std::int32_t>(a));
  }
  double energy = 0.0;
  for (std::size_t a = 0; a < nc; ++a) {
    const bool a_owned = a < owned;
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, home[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      const int n = cells[k];
      home[k] = cell_of[a * D + k];
      if (n < 3) {
        lo[k] = -home[k], hi[k] = n - 1 - home[k];
      } else if (WallsY && k == 1) {
        lo[k] = home[k] > 0 ? -1 : 0, hi[k] = home[k] < n - 1 ? 1 : 0;
      } else {
        lo[k] = -1, hi[k] = 1;
      }
    }
    partners.clear();
    int off[3] = {0, 0, 0};
    for (off[2] = lo[2]; off[2] <= hi[2]; ++off[2])
      for (off[1] = lo[1]; off[1] <= hi[1]; ++off[1])
        for (off[0] = lo[0]; off[0] <= hi[0]; ++off[0]) {
          std::size_t cell = 0;
          for (int k = D - 1; k >= 0; --k) {
            const int n = cells[k];
            int ck = home[k] + off[k];
            ck = ck < 0 ? ck + n : (ck >= n ? ck - n : ck);
            cell = cell * static_cast<std::size_t>(n) + static_cast<std::size_t>(ck);
          }
          for (std::int32_t b = cl.head[cell]; b >= 0; b = cl.next[b])
            if (static_cast<std::size_t>(b) > a)
              partners.push_back(static_cast<std::uint32_t>(b));
        }
    if (want_energy)
      std::sort(partners.begin(), partners.end());
    const double xa[3] = {c.x[0][a], c.x[1][a], D == 3 ? c.x[2][a] : 0.0};
    for (const std::uint32_t b : partners) {
      const double xb[3] = {c.x[0][b], c.x[1][b], D == 3 ? c.x[2][b] : 0.0};
      double d[3];
      const double r2 = separation<D, WallsY>(xa, xb, L, d);
      const double scc = c.radius[a] + c.radius[b];
      if (r2 >= std::pow(repulsive_cutoff(24, scc), 2))
        continue;
      const bool b_owned = b < owned;
      if (!a_owned && !b_owned)
        continue;
      const PairTerm t = repulsive_pair<24>(r2, scc * scc, eps);
      if ((a_owned && b_owned) || (a_owned ? c.id[a] < c.id[b] : c.id[b] < c.id[a]))
        energy += t.energy;
      for (int k = 0; k < D; ++k) {
        const std::int64_t q = to_fixed(t.f_over_r * d[k]);
        if (a_owned)
          on_colloids[a * D + k] += q;
        if (b_owned)
          on_colloids[static_cast<std::size_t>(b) * D + k] -= q;
      }
    }
  }
  return energy;
}

#define NARROWS_INSTANTIATE(D, W)                                                                  \
  template double add_colloid_colloid_4824<D, W>(                                                  \
      CellList &, std::vector<int> &, std::vector<std::uint32_t> &, const Colloids &, std::size_t, \
      const mpcd::Box &, double, bool, std::vector<std::int64_t> &);
NARROWS_FOR_EACH_DIM_AND_WALLS(NARROWS_INSTANTIATE)
#undef NARROWS_INSTANTIATE

} // namespace narrows::colloids
