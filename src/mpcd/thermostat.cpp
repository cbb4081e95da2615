// The per-layer rescaling thermostat of seed 000 eq 3.53-3.54.
#include "narrows/mpcd/thermostat.hpp"

#include "narrows/core/fixed_point.hpp"

#include <cmath>

namespace narrows::mpcd {

void rescale_layers(Fluid &f, const CellGrid &grid, double kT, LayerSums &s, MPI_Comm comm) {
  const int d = f.dim;
  const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
  const std::size_t ny = static_cast<std::size_t>(grid.cells[1]);
  const std::size_t n = f.size();
  auto layer_of = [&](std::size_t c) { return (c / nx) % ny; };
  // Cell mean velocities of the particles as they are now (fixed point: order-independent).
  const std::size_t nc = grid.size();
  s.cell_p.assign(nc * d, 0);
  s.cell_n.assign(nc, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = f.cell[i];
    for (int k = 0; k < d; ++k)
      s.cell_p[c * d + k] += fixed::from_double(f.v[k][i]);
    ++s.cell_n[c];
  }
  auto mean = [&](std::size_t c, int k) {
    return fixed::to_double(s.cell_p[c * d + k]) / static_cast<double>(s.cell_n[c]);
  };
  s.local.assign(3 * ny, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = f.cell[i];
    double e = 0.0;
    for (int k = 0; k < d; ++k) {
      const double r = f.v[k][i] - mean(c, k);
      e += r * r;
    }
    s.local[3 * layer_of(c)] += fixed::from_double(e);
    s.local[3 * layer_of(c) + 1] += 1;
  }
  for (std::size_t c = 0; c < nc; ++c)
    s.local[3 * layer_of(c) + 2] += s.cell_n[c] > 0 ? 1 : 0;
  if (comm == MPI_COMM_NULL) {
    s.global = s.local;
  } else {
    s.global.resize(s.local.size());
    MPI_Allreduce(s.local.data(), s.global.data(), static_cast<int>(s.local.size()), MPI_INT64_T,
                  MPI_SUM, comm);
  }
  std::vector<double> scale(ny, 1.0);
  for (std::size_t l = 0; l < ny; ++l) {
    const double e = fixed::to_double(s.global[3 * l]);
    const double dof =
        static_cast<double>(d) * static_cast<double>(s.global[3 * l + 1] - s.global[3 * l + 2]);
    if (dof > 0.0 && e > 0.0)
      scale[l] = std::sqrt(kT * dof / e); // kT' = e / dof (mass 1)
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = f.cell[i];
    const double a = scale[layer_of(c)];
    for (int k = 0; k < d; ++k) {
      const double u = mean(c, k);
      f.v[k][i] = u + (f.v[k][i] - u) * a;
    }
  }
}

} // namespace narrows::mpcd
