// The per-layer rescaling thermostat of Tabatabaei (2008) eq 3.53-3.54.
#include "narrows/engines/mpcd/kernels/thermostat.hpp"

#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"

#include <cmath>

namespace narrows::mpcd {

namespace {

// Cell momenta and counts of the particles as they are now (fixed point: order-independent).
void sum_cells(const Fluid &f, std::size_t cells, LayerSums &s) {
  const int d = f.dim;
  s.cell_p.assign(cells * d, 0);
  s.cell_n.assign(cells, 0);
  for (std::size_t i = 0; i < f.size(); ++i) {
    const std::size_t c = f.cell[i];
    for (int k = 0; k < d; ++k)
      s.cell_p[c * d + k] += fixed::from_double(f.v[k][i]);
    ++s.cell_n[c];
  }
}

// Mean velocity component k of cell c (after sum_cells).
inline double cell_mean(const LayerSums &s, int d, std::size_t c, int k) {
  return fixed::to_double(s.cell_p[c * d + k]) / static_cast<double>(s.cell_n[c]);
}

// |v_i - u|^2 of particle i relative to its cell's mean.
inline double relative_v2(const Fluid &f, const LayerSums &s, std::size_t i) {
  double e = 0.0;
  for (int k = 0; k < f.dim; ++k) {
    const double r = f.v[k][i] - cell_mean(s, f.dim, f.cell[i], k);
    e += r * r;
  }
  return e;
}

// v_i = u + a (v_i - u) for particle i.
inline void scale_relative(Fluid &f, const LayerSums &s, std::size_t i, double a) {
  for (int k = 0; k < f.dim; ++k) {
    const double u = cell_mean(s, f.dim, f.cell[i], k);
    f.v[k][i] = u + (f.v[k][i] - u) * a;
  }
}

} // namespace

void rescale_layers(Fluid &f, const CellGrid &grid, double kT, LayerSums &s, MPI_Comm comm) {
  const int d = f.dim;
  const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
  const std::size_t ny = static_cast<std::size_t>(grid.cells[1]);
  const std::size_t n = f.size();
  auto layer_of = [&](std::size_t c) { return (c / nx) % ny; };
  const std::size_t nc = grid.size();
  sum_cells(f, nc, s);
  s.local.assign(3 * ny, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t l = layer_of(f.cell[i]);
    s.local[3 * l] += fixed::from_double(relative_v2(f, s, i));
    s.local[3 * l + 1] += 1;
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
  for (std::size_t i = 0; i < n; ++i)
    scale_relative(f, s, i, scale[layer_of(f.cell[i])]);
}

void monte_carlo_cells(Fluid &f, const CellGrid &grid, double kT, double gamma, std::uint64_t seed,
                       std::uint64_t step, LayerSums &s) {
  const int d = f.dim;
  const std::size_t n = f.size(), nc = grid.size();
  sum_cells(f, nc, s);
  // Relative kinetic energy per cell, in fixed point (s.local reused as per-cell storage).
  s.local.assign(nc, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.local[f.cell[i]] += fixed::from_double(0.5 * relative_v2(f, s, i));
  // The factor of each cell (1 = rejected or fewer than 2 particles).
  std::vector<double> &zeta = s.zeta;
  zeta.assign(nc, 1.0);
  for (std::size_t c = 0; c < nc; ++c) {
    if (s.cell_n[c] < 2)
      continue;
    const auto r = rng::draw(seed, rng::Purpose::mc_thermostat, step, grid.global_id(c));
    const double eps = gamma * rng::open01(r[0]);
    const double z = (r[1] & 1u) ? 1.0 + eps : 1.0 / (1.0 + eps);
    const double dof = static_cast<double>(d) * (s.cell_n[c] - 1.0);
    const double e = fixed::to_double(s.local[c]);
    const double log_accept = dof * std::log(z) - (z * z - 1.0) * e / kT;
    if (log_accept >= 0.0 || rng::open01(r[2]) < std::exp(log_accept))
      zeta[c] = z;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (zeta[f.cell[i]] != 1.0)
      scale_relative(f, s, i, zeta[f.cell[i]]);
}

} // namespace narrows::mpcd
