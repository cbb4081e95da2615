// Forces of the integrated Lennard-Jones walls on the colloids (Tabatabaei (2008) eq 3.35-3.37).
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/potentials.hpp"

#include <sstream>

namespace narrows::colloids {

template <int D>
double add_wall_lj(const Colloids &c, std::size_t owned, const mpcd::Box &box, double eps,
                   double sigma_wall, double wall_q, std::vector<std::int64_t> &on_colloids) {
  const auto &L = box.length;
  double energy = 0.0;
  for (std::size_t a = 0; a < owned; ++a) {
    const double sw = sigma_wall > 0.0 ? sigma_wall : 2.0 * c.radius[a];
    const double hcut = wall_cutoff(sw), y = c.x[1][a];
    if (!(y > 0.0 && y < L[1])) {
      std::ostringstream os;
      os.precision(17);
      os << "colloid id " << c.id[a] << " is outside the channel at y = " << y
         << " (allowed: 0 < y < " << L[1] << ")";
      throw invariant_error(os.str());
    }
    if (y < hcut) {
      const WallTerm w = wall_term(y, sw, eps, wall_q);
      energy += w.energy;
      on_colloids[a * D + 1] += to_fixed(w.force);
    }
    if (L[1] - y < hcut) {
      const WallTerm w = wall_term(L[1] - y, sw, eps, wall_q);
      energy += w.energy;
      on_colloids[a * D + 1] -= to_fixed(w.force);
    }
  }
  return energy;
}

template double add_wall_lj<2>(const Colloids &, std::size_t, const mpcd::Box &, double, double,
                               double, std::vector<std::int64_t> &);
template double add_wall_lj<3>(const Colloids &, std::size_t, const mpcd::Box &, double, double,
                               double, std::vector<std::int64_t> &);

} // namespace narrows::colloids
