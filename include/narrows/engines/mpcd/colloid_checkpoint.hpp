// Colloids in checkpoints: the species "colloids" (every field its table stores: position,
// velocity, id, radius, mass, angular velocity, orientation, and any added ones), all rows in id
// order (gathered from their owners: MpcdSimulation::gather_colloids), so rank 0
// writes them and on reading every rank gets all of them back and keeps its own. Radius and mass
// are stored so a restart restores them exactly; checkpoints from before they were stored get them
// from the scene (set_radii_and_masses, colloid_placement.hpp).
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <cstdint>
#include <string>

namespace narrows::mpcd {

// The colloids as a species for write_checkpoint: all rows on rank 0, none elsewhere (`empty`
// is the empty storage the other ranks point at).
io::SpeciesFields colloid_fields(colloids::Colloids &c, colloids::Colloids &empty, MPI_Comm comm);

// All colloids of a checkpoint on every rank, in id order, radius and mass as stored (older
// checkpoints: from the scene and `seed`) (collective). input_error if the species is missing,
// its count differs from the scene's, or a stored radius or mass is not a finite number > 0.
// With `like`, the colloids also have its added fields (species::Extra), read if stored.
colloids::Colloids read_colloids(const std::string &path, const scene::Colloids &spec, int dim,
                                 double density, std::uint64_t seed, MPI_Comm comm,
                                 const colloids::Colloids *like = nullptr);

// The contact history of spring contacts as the species "contacts" (owner_id, partner_id,
// tangential_displacement; partner ids 2^64 - 1 and 2^64 - 2 are the walls at y = 0 and L_y),
// all rows in key order on rank 0, none elsewhere.
io::SpeciesFields contact_fields(colloids::ContactHistory &all, colloids::ContactHistory &empty,
                                 MPI_Comm comm);

// All contacts of a checkpoint on every rank, in key order (collective); empty if the
// checkpoint has none (written before contacts had a history). input_error naming the dataset
// and row for a damaged one: an id outside the colloids, a partner not above its owner (or a
// wall without walls), a key twice, a displacement that is not finite.
colloids::ContactHistory read_contacts(const std::string &path, std::int64_t colloids, int dim,
                                       bool walls, MPI_Comm comm);

} // namespace narrows::mpcd
