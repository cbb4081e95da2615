// Virtual wall particles (Tabatabaei (2008) §3.2.5, eq 3.14): cells cut by a wall hold fewer
// particles than the bulk, which weakens the no-slip condition; virtual particles at rest on
// average fill them to the mean density. Only their number and summed velocities enter the
// collision, so they are drawn as one Gaussian per component with variance (n - n_cell) kT.
#pragma once

#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <cstdint>

namespace narrows::walls {

// Lists the cut cells (the first and last rows of a grid with walls) that hold fewer than
// `density` particles, with the virtual particles' count, summed momentum and, if `at_noise`,
// the sum of their MPC-AT Gaussian velocities; draws keyed by (seed, step, global cell).
// With `mirror`, their mean velocity continues the flow antisymmetrically through the wall
// instead of resting: a cut cell whose fluid part is s thick (0 <= s < 1) gets virtual
// particles with mean velocity -u_next (1 - s)/(1 + 2s), u_next the mean velocity of the
// neighbouring row, which is exact for a linear profile vanishing at the wall; the Gaussian
// keeps the total variance (n - n_cell) kT (less what u_next's own noise contributes).
void add_virtual_particles(mpcd::CellGrid &grid, double density, double kT, std::uint64_t seed,
                           std::uint64_t step, bool at_noise, bool mirror = false);

} // namespace narrows::walls
