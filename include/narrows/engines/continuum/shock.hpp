// Where the shock of a 1D density profile is: the steepest jump between neighbouring cells,
// located to a fraction of a cell where the profile crosses the mid level of the densities
// `halo` cells either side of it.
#pragma once

#include <cstddef>
#include <vector>

namespace narrows::continuum {

// Position in [0, cells dx] of the steepest jump of the cell averages u (cell i centred at
// (i + 1/2) dx); periodic profiles wrap.
double shock_position(const std::vector<double> &u, double dx, bool periodic, std::size_t halo = 4);

} // namespace narrows::continuum
