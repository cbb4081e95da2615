// The MPCD fluid in a checkpoint: the species "fluid" of io/checkpoint.hpp (position, velocity,
// id), and the fluid of a checkpoint read back.
#pragma once

#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/io/checkpoint.hpp"

#include <mpi.h>

#include <string>

namespace narrows::mpcd {

// The fluid as a checkpoint species: the fields its table stores (position, velocity, id).
io::SpeciesFields fluid_fields(mpcd::Fluid &fluid);

// The fluid of a checkpoint: this rank's block of rows, cell indices zero (recomputed by the
// next step). input_error if the checkpoint's data were not made with its stored scene, or the
// fluid is one a run cannot continue (restart_checks.hpp; thrown collectively or after the
// collective reads, so it can be agreed on with run::collectively).
mpcd::Fluid read_fluid(const std::string &path, const io::CheckpointInfo &info, MPI_Comm comm);

} // namespace narrows::mpcd
