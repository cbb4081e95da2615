// Virtual particles in the cells cut by the walls.
#include "narrows/walls/virtual_particles.hpp"

#include "narrows/core/rng.hpp"

#include <cmath>

namespace narrows::walls {

void add_virtual_particles(mpcd::CellGrid &grid, double density, double kT, std::uint64_t seed,
                           std::uint64_t step, bool at_noise) {
  grid.virtual_cells.clear();
  const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
  const std::size_t rows = static_cast<std::size_t>(grid.cells[1]);
  const std::size_t planes = static_cast<std::size_t>(grid.dim == 3 ? grid.cells[2] : 1);
  for (std::size_t z = 0; z < planes; ++z)
    for (const std::size_t row : {std::size_t{0}, rows - 1})
      for (std::size_t ix = 0; ix < nx; ++ix) {
        const std::size_t c = ix + nx * (row + rows * z);
        const double missing = density - grid.sums[c].n;
        if (missing <= 0.0)
          continue;
        mpcd::VirtualCell v;
        v.cell = static_cast<std::uint32_t>(c);
        v.count = missing;
        const double sigma = std::sqrt(missing * kT);
        const std::uint64_t id = grid.global_id(c);
        const auto p =
            rng::gaussian4(rng::draw(seed, rng::Purpose::wall_virtual_momentum, step, id));
        for (int k = 0; k < grid.dim; ++k)
          v.momentum[k] = sigma * p[k];
        if (at_noise) {
          const auto q =
              rng::gaussian4(rng::draw(seed, rng::Purpose::wall_virtual_noise, step, id));
          for (int k = 0; k < grid.dim; ++k)
            v.noise[k] = sigma * q[k];
        }
        grid.virtual_cells.push_back(v);
      }
}

} // namespace narrows::walls
