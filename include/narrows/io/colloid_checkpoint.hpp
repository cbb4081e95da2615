// Colloids in checkpoints: the species "colloids" (position, velocity, id). Every rank holds
// all colloids, so rank 0 writes them and on reading every rank gets all of them back.
// Radius and mass follow from the scene (monodisperse) and are not stored.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>

namespace narrows::io {

// The colloids as a species for write_checkpoint: all rows on rank 0, none elsewhere (`empty`
// is the empty storage the other ranks point at).
SpeciesFields colloid_fields(colloids::Colloids &c, colloids::Colloids &empty, MPI_Comm comm);

// All colloids of a checkpoint on every rank, in id order, radius and mass from the scene
// (collective). input_error if the species is missing or its count differs from the scene's.
colloids::Colloids read_colloids(const std::string &path, const scene::Colloids &spec, int dim,
                                 double density, MPI_Comm comm);

} // namespace narrows::io
