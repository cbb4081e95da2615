// Checks of a restarted MPCD state that need more than one species (issue 18 item 6): what
// io::validate_particles cannot see field by field.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <mpi.h>

#include <string>

namespace narrows::mpcd {

// Refuses (input_error, collectively: every rank ends with the same one line, exit 2) a
// restarted fluid with a particle inside a colloid where no running simulation can have put
// it: its WCA pair force (Tabatabaei (2008) eq 3.42, sigma = the colloid's radius, strength
// `epsilon`) has a component beyond the fixed-point range (fixed::max_magnitude), at which the
// force loop of a run stops with exit 3 (colloids/pair_geometry.hpp, to_fixed). The line names
// `file`, /particles/fluid/position/value, the fluid id (the smallest such id on any rank), the
// colloid id, the distance and the pair energy in units of `kT`.
//
// `local_fluid`: this rank's fluid; `all_colloids`: every colloid (on every rank). Fluid and
// colloids are binned by the largest cut-off, so the cost is O(N + Nc) for colloids that do not
// overlap.
void check_fluid_outside_colloids(const mpcd::Fluid &local_fluid,
                                  const colloids::Colloids &all_colloids, const mpcd::Box &box,
                                  double epsilon, double kT, const std::string &file,
                                  MPI_Comm comm);

} // namespace narrows::mpcd
