// Collision rules of the MPCD fluid. Each acts on particles already binned into the shifted
// grid (bin_particles) and uses counter-based random numbers keyed by (seed, step, cell or id).
#pragma once

#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <cstdint>
#include <vector>

namespace narrows::mpcd {

// Scratch space the rules reuse between steps (no allocation in the step loop).
struct CollisionScratch {
  std::vector<double> cell;                 // per-cell parameters, rule-specific stride
  std::array<std::vector<double>, 3> noise; // per-particle Gaussian velocities (AT rules)
  std::vector<std::int64_t> cell_fixed;     // per-cell fixed-point sums beyond momentum
  std::vector<GroupChange> group_change;    // per grid.groups entry, what the collision did
  // The largest |v|^2 of the fluid the last collision left, found on its way (MPC-AT+a; -1:
  // not known): the next step's fluid reach (colloids/near_fluid.hpp) without a pass of its own.
  double v2_max = -1.0;
  // MPC-AT+a: cell_fixed holds, from entry position_offset of each cell's record of
  // position_stride, the cell's summed in-cell offsets (fixed point; fluid and groups), which
  // the no-slip coupling reads instead of summing its cut cells' fluid again. 0: not kept.
  int position_stride = 0, position_offset = 0;
  // MPC-AT+a between its cells and its particles (collide_at_a_cells, then _particles):
  // cells_pending. With room for shifts, cell holds records of shift_stride doubles; from entry
  // shift_offset, a velocity change c (D entries) and spin w (1 | 3) that the particle pass
  // adds to each new velocity as c + w x r (r from the cell's corner), zero unless a coupling
  // writes them and sets cells_shifted. shift_stride = 0: no room (or no collision pending).
  bool cells_pending = false;
  int shift_stride = 0, shift_offset = 0;
  bool cells_shifted = false;
};

// Every rule below (not the random solvents' own steps) also collides the particle groups of
// grid.groups as if their particles were listed (SRD: rotated about the cell mean; AT: the
// groups' xi; AT+a: their positions' moments enter the cell's centre, moment of inertia and
// angular momentum) and writes each group's change to scratch.group_change.

// SRD: rotate velocities relative to the cell mean by +-alpha (2D, sign random per cell) or
// by alpha about a random unit axis (3D). Conserves momentum and kinetic energy per cell.
void collide_srd(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double angle_rad,
                 std::uint64_t seed, std::uint64_t step);

// MPC-AT (Andersen thermostat): v_i' = u + xi_i - <xi>_cell with xi Gaussian at kT.
// Conserves momentum per cell.
void collide_at(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double kT,
                std::uint64_t seed, std::uint64_t step);

// MPC-AT+a: MPC-AT plus the rigid-rotation correction that restores each cell's angular
// momentum (Noguchi et al. (2007)). Cells whose moment of inertia is singular (one particle; two
// in 3D, collinear) use the pseudo-inverse, which is exact there.
void collide_at_a(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double kT,
                  std::uint64_t seed, std::uint64_t step);
// The same in two passes, for a coupling that changes the cells' velocities in between: the
// cells (their records, the groups' change; with room_for_shifts, room in each record for the
// coupling's change), then the particles' new velocities.
void collide_at_a_cells(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch, double kT,
                        std::uint64_t seed, std::uint64_t step, bool room_for_shifts);
void collide_at_a_particles(Fluid &fluid, const CellGrid &grid, CollisionScratch &scratch);

// Random solvent (a): after the collision, a random permutation of all fluid velocities.
// Conserves total momentum and energy, destroys local momentum conservation.
void permute_velocities(Fluid &fluid, CollisionScratch &scratch, std::uint64_t seed,
                        std::uint64_t step);

// Random solvent (b): every fluid particle gets a fresh Maxwell-Boltzmann velocity at kT.
void draw_maxwell_velocities(Fluid &fluid, double kT, std::uint64_t seed, std::uint64_t step);

} // namespace narrows::mpcd
