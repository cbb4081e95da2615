// A species table (species/table.hpp) as the fields of a checkpoint: the datasets, names and
// shapes io/checkpoint.hpp writes and reads, for the fields flagged species::checkpoint.
#pragma once

#include "narrows/io/checkpoint.hpp"
#include "narrows/species/table.hpp"

#include <mpi.h>

#include <functional>
#include <string>

namespace narrows::io {

// The stored fields of t: vector fields as [N][d] float64, uint64 scalars as [N] uint64 words,
// double scalars as [N] float64, split fields as one [N] float64 dataset per stored column
// (<name>_<suffix>). `skip(field)` leaves fields out (those an older checkpoint lacks, on
// reading). A stored field of another type is an error (nothing stores one).
SpeciesFields checkpoint_fields(const species::Table &t,
                                const std::function<bool(const species::Field &)> &skip = {});

// Whether the checkpoint at `path` holds any dataset of field f of t (collective): false for a
// field added after the checkpoint was written.
bool has_checkpoint_field(const std::string &path, const species::Table &t, const species::Field &f,
                          MPI_Comm comm);

} // namespace narrows::io
