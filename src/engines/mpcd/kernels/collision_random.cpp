// Random solvents (Tabatabaei (2008) section 4.3): hydrodynamic interactions switched off.
#include "narrows/core/rng.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"

#include <cmath>
#include <utility>

namespace narrows::mpcd {

void permute_velocities(Fluid &fluid, CollisionScratch &, std::uint64_t seed, std::uint64_t step) {
  // Fisher-Yates over the local array, one counter-based draw per position: a permutation of
  // all fluid velocities on one rank (the engine refuses it on more, mpcd::check_ranks).
  const std::size_t n = fluid.size();
  for (std::size_t i = n; i > 1; --i) {
    const auto r = rng::draw(seed, rng::Purpose::random_permute, step, i);
    const std::uint64_t u = (static_cast<std::uint64_t>(r[0]) << 32) | r[1];
    // Multiply-shift maps u uniformly onto [0, i) up to a bias of i / 2^64.
    const auto j = static_cast<std::size_t>((static_cast<unsigned __int128>(u) * i) >> 64);
    for (int k = 0; k < fluid.dim; ++k)
      std::swap(fluid.v[k][i - 1], fluid.v[k][j]);
  }
}

void draw_maxwell_velocities(Fluid &fluid, double kT, std::uint64_t seed, std::uint64_t step) {
  const double sigma = std::sqrt(kT);
  const std::size_t n = fluid.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto g = rng::gaussian4(rng::draw(seed, rng::Purpose::random_maxwell, step, fluid.id[i]));
    for (int k = 0; k < fluid.dim; ++k)
      fluid.v[k][i] = sigma * g[k];
  }
}

} // namespace narrows::mpcd
