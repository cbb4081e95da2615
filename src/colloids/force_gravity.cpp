// Gravity on the colloids: the force M_a g (Tabatabaei (2008) eq 4.4).
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/pair_geometry.hpp"

namespace narrows::colloids {

template <int D>
void add_gravity(const Colloids &c, std::size_t owned, const std::array<double, 3> &g,
                 std::vector<std::int64_t> &on_colloids) {
  for (int k = 0; k < D; ++k)
    if (g[k] != 0.0)
      for (std::size_t a = 0; a < owned; ++a)
        on_colloids[a * D + k] += to_fixed(c.mass[a] * g[k]);
}

template void add_gravity<2>(const Colloids &, std::size_t, const std::array<double, 3> &,
                             std::vector<std::int64_t> &);
template void add_gravity<3>(const Colloids &, std::size_t, const std::array<double, 3> &,
                             std::vector<std::int64_t> &);

} // namespace narrows::colloids
