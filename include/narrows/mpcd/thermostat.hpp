// Per-layer velocity rescaling thermostat (seed 000 eq 3.53-3.54): in each layer of collision
// cells (a row at fixed y, spanning x and z over all ranks) the velocities relative to their
// cell's mean velocity are scaled by sqrt(kT / kT'), where kT' is the layer's temperature
// measured relative to the cell means: sum_i m (v_i - u_cell)^2 / 2 = (d/2)(N_layer - C_layer) kT'
// (C_layer = occupied cells; each cell's mean removes d degrees of freedom). Cell momenta are
// unchanged; the layer's relative kinetic energy becomes (d/2)(N - C) kT.
#pragma once

#include "narrows/mpcd/cell_grid.hpp"
#include "narrows/mpcd/fluid.hpp"

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace narrows::mpcd {

// Scratch of the thermostat, reused between steps.
struct LayerSums {
  std::vector<std::int64_t> local, global; // per layer: sum (v - u)^2 (fixed point), N, C
  std::vector<std::int64_t> cell_p;        // per cell: momentum (fixed point), d per cell
  std::vector<std::uint32_t> cell_n;       // per cell: particles
};

// Applies the thermostat to the binned fluid (the cell indices of this step's grid; the cell
// means are summed afresh, as the collision and virtual particles changed them); the
// layer sums are reduced over comm in fixed point, so the result is the same on any number of
// ranks. comm = MPI_COMM_NULL: this process alone, without MPI (unit tests).
void rescale_layers(Fluid &fluid, const CellGrid &grid, double kT, LayerSums &scratch,
                    MPI_Comm comm);

} // namespace narrows::mpcd
