// Thermostats of Tabatabaei (2008) §3.4.6.
//
// Per-layer velocity rescaling (eq 3.53-3.54): in each layer of collision
// cells (a row at fixed y, spanning x and z over all ranks) the velocities relative to their
// cell's mean velocity are scaled by sqrt(kT / kT'), where kT' is the layer's temperature
// measured relative to the cell means: sum_i m (v_i - u_cell)^2 / 2 = (d/2)(N_layer - C_layer) kT'
// (C_layer = occupied cells; each cell's mean removes d degrees of freedom). Cell momenta are
// unchanged; the layer's relative kinetic energy becomes (d/2)(N - C) kT.
//
// Monte Carlo cell thermostat (eq 3.55-3.57): in every cell with n >= 2 particles the velocities
// relative to the cell mean are scaled by zeta = 1 + eps or 1/(1 + eps) (eps uniform in
// [0, gamma], either with probability 1/2), accepted with probability
//   min(1, zeta^(d(n-1)) exp(-(zeta^2 - 1) E / kT)),  E = sum_i m (v_i - u)^2 / 2,
// which is detailed balance for the Boltzmann weight of the d(n-1) relative degrees of freedom
// (the dissertation prints the 3D exponent 3(n-1) and writes E as (n-1) T with its eq 3.57).
#pragma once

#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace narrows::mpcd {

// Scratch of the thermostat, reused between steps.
struct LayerSums {
  std::vector<std::int64_t> local, global; // per layer: sum (v - u)^2 (fixed point), N, C
  std::vector<std::int64_t> cell_p;        // per cell: momentum (fixed point), d per cell
  std::vector<std::uint32_t> cell_n;       // per cell: particles
  std::vector<double> zeta;                // per cell: Monte Carlo scale factor
};

// Applies the thermostat to the binned fluid (the cell indices of this step's grid; the cell
// means are summed afresh, as the collision and virtual particles changed them); the
// layer sums are reduced over comm in fixed point, so the result is the same on any number of
// ranks. comm = MPI_COMM_NULL: this process alone, without MPI (unit tests).
void rescale_layers(Fluid &fluid, const CellGrid &grid, double kT, LayerSums &scratch,
                    MPI_Comm comm);

// Applies the Monte Carlo cell thermostat; draws keyed by (seed, step, global cell index), cell
// sums in fixed point, so the result is the same on any number of ranks.
void monte_carlo_cells(Fluid &fluid, const CellGrid &grid, double kT, double gamma,
                       std::uint64_t seed, std::uint64_t step, LayerSums &scratch);

} // namespace narrows::mpcd
