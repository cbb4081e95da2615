// The fluid particles that take part in the MD sub-steps of a step (md_integrator.hpp).
//
// Only fluid particles that can come within the WCA cut-off of a colloid during the step take
// part: a particle is left out when its distance to every colloid exceeds r_cut + (its largest
// possible path |v| dt + |a| dt^2/2) + margin[a] (the colloid's possible path |V| dt + |F|/M
// dt^2 + 0.25: twice the constant-force value, plus an allowance for the fluid's kicks within
// the step). Those far particles stream the whole step at once; the near ones stream between
// the velocity-Verlet kicks.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/forces.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <cstdint>
#include <vector>

namespace narrows::coupling {

// The largest possible path |v| dt + |a| dt^2/2 of any particle of f this step; v2_max: the
// largest |v|^2 if already known (>= 0), else a pass over f finds it.
double fluid_reach(const mpcd::Fluid &f, double dt, double fluid_accel, double v2_max = -1.0);

// Lists in `index` (flags in `flag`) the particles of f near a colloid of c (owned and ghost
// rows, margin[a] for each) this step, from the cell list `cells` of f (built by the force
// evaluation just before); max_reach = fluid_reach(f, dt, fluid_accel).
void select_near_fluid(const colloids::CellList &cells, const mpcd::Fluid &f,
                       const colloids::Colloids &c, const mpcd::Box &box,
                       const std::vector<double> &margin, double dt, double fluid_accel,
                       double max_reach, std::vector<std::uint8_t> &flag,
                       std::vector<std::uint32_t> &index);

} // namespace narrows::coupling
