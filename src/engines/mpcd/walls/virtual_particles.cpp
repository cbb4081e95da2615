// Virtual particles in the cells cut by the walls.
#include "narrows/engines/mpcd/walls/virtual_particles.hpp"

#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"

#include <algorithm>
#include <array>

#include <cmath>

namespace narrows::walls {

void add_virtual_particles(mpcd::CellGrid &grid, double density, double kT, std::uint64_t seed,
                           std::uint64_t step, bool at_noise, bool mirror) {
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
        double variance = missing * kT;
        std::array<double, 3> mean{0.0, 0.0, 0.0};
        if (mirror) {
          // Fluid thickness of the cut cell and the neighbouring row's mean velocity.
          const double s = row == 0 ? grid.shift[1] : 1.0 - grid.shift[1];
          const mpcd::CellSums &next = grid.sums[row == 0 ? c + nx : c - nx];
          if (next.n > 0) {
            const double f = missing * (1.0 - s) / (1.0 + 2.0 * s) / next.n;
            for (int k = 0; k < grid.dim; ++k)
              mean[k] = -f * fixed::to_double(next.p[k]);
            variance = std::max(0.0, variance - f * f * next.n * kT);
          }
        }
        const double sigma = std::sqrt(variance);
        const std::uint64_t id = grid.global_id(c);
        const auto p =
            rng::gaussian4(rng::draw(seed, rng::Purpose::wall_virtual_momentum, step, id));
        for (int k = 0; k < grid.dim; ++k)
          v.momentum[k] = mean[k] + sigma * p[k];
        if (at_noise) {
          const double sigma_noise = std::sqrt(missing * kT);
          const auto q =
              rng::gaussian4(rng::draw(seed, rng::Purpose::wall_virtual_noise, step, id));
          for (int k = 0; k < grid.dim; ++k)
            v.noise[k] = sigma_noise * q[k];
        }
        grid.virtual_cells.push_back(v);
      }
}

} // namespace narrows::walls
