// Colloid-colloid 48-24 forces (Tabatabaei (2008) eq 3.43) from a cell list of the colloids.
#include "narrows/colloids/colloid_pairs.hpp"
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/potentials.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::colloids {

template <int D, bool WallsY>
double add_colloid_colloid_4824(CellList &cl, std::vector<int> &cell_of,
                                std::vector<std::uint32_t> &partners, const Colloids &c,
                                std::size_t owned, const mpcd::Box &box, double eps,
                                bool want_energy, std::vector<std::int64_t> &on_colloids) {
  // Colloid a meets the partners b > a in the cells within one of its own (colloid_pairs.hpp).
  // The pair forces are rounded to fixed point and summed as integers, so the order of the pairs
  // does not matter; the energy is a sum of doubles, so for it the partners of each a are taken in
  // increasing b, the order of a double loop over a < b. Rows from `owned` on are ghost copies
  // (ghosts.hpp): a pair adds only to its owned rows (the owner of the other side adds its half
  // from the same positions, bitwise the negative), pairs of two ghosts are left to their owners,
  // and the energy of a pair with a ghost is counted on the rank that owns the colloid with the
  // smaller id.
  const auto &L = box.length;
  double energy = 0.0;
  for_each_colloid_pair<D, WallsY>(
      cl, cell_of, partners, c, [&](std::size_t a, std::vector<std::uint32_t> &near) {
        const bool a_owned = a < owned;
        if (want_energy)
          std::sort(near.begin(), near.end());
        const double xa[3] = {c.x[0][a], c.x[1][a], D == 3 ? c.x[2][a] : 0.0};
        for (const std::uint32_t b : near) {
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
      });
  return energy;
}

#define NARROWS_INSTANTIATE(D, W)                                                                  \
  template double add_colloid_colloid_4824<D, W>(                                                  \
      CellList &, std::vector<int> &, std::vector<std::uint32_t> &, const Colloids &, std::size_t, \
      const mpcd::Box &, double, bool, std::vector<std::int64_t> &);
NARROWS_FOR_EACH_DIM_AND_WALLS(NARROWS_INSTANTIATE)
#undef NARROWS_INSTANTIATE

} // namespace narrows::colloids
