// Colloids as a species owned by slabs (issue 16 item 4): each colloid belongs to the rank
// whose slab holds its centre, by the unshifted cell column of x; between MPCD steps a rank
// holds exactly the colloids it owns, in id order. Every per-colloid field that migrates (the
// colloid table: colloids.hpp) travels with the colloid; observables and checkpoints gather all
// of them in id order.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/parallel/exchange.hpp"
#include "narrows/parallel/slabs.hpp"

#include <mpi.h>

namespace narrows::colloids {

// The rank that owns colloid a: the owner of the cell column of its centre.
inline int owner_of(const Colloids &c, std::size_t a, const parallel::Slabs &slabs) {
  return slabs.owner(mpcd::cell_coordinate(c.x[0][a], 0.0, slabs.columns(), 0, "colloid", c.id[a]));
}

// Keeps the colloids this rank owns (of a set every rank holds whole), in id order.
void keep_owned(Colloids &c, const parallel::Slabs &slabs);

// Sends each colloid whose centre left this rank's slab to its new owner and restores id order
// (collective).
void migrate_colloids(Colloids &c, const parallel::Slabs &slabs, parallel::Exchange &exchange);

// All colloids of every rank, in id order, on every rank (collective): for observables,
// trajectories and checkpoints, which read the whole species.
Colloids gather_colloids(const Colloids &owned, MPI_Comm comm);

} // namespace narrows::colloids
