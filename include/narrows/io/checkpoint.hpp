// Checkpoints: one parallel-HDF5 file per checkpoint, its structure created collectively (the
// particle datasets contiguous, allocated at creation), then each rank's rows written at its
// MPI_Exscan offset straight to the disk (io/direct_writer: O_DIRECT where the file system
// allows it); read back collectively on any number of ranks (each rank a block of rows; the
// first step migrates the particles to their slab owners).
//
// Layout (H5MD style, format version 1):
//   /h5md                      attribute version = [1, 1]; groups creator, author (name, ...)
//   /particles/<species>/box   attributes dimension, boundary; dataset edges [d]
//   /particles/<species>/<field>/{value, step, time}
//                              vector fields (position, velocity): value [N][d] float64
//                              word fields (id): value [N] uint64
//                              scalar fields (colloid radius, mass): value [N] float64
//   /parameters/{scene, step, time, seed, format_version, dimensions}
//   /parameters/canonical_scene   the scene as scene/canonical.hpp writes it (for restarts;
//                              older checkpoints lack it: their scene is canonicalised)
//   /<engine>/<name>           engine-specific small arrays (CheckpointArray), e.g. /kmc/...
//
// Species are generic: a species is a name plus its vector, word and scalar fields
// (SpeciesFields, derived from the species' table: io/species_fields.hpp), and the writer/reader
// loop over whatever a run has: the fluid "fluid", the colloids "colloids" (with radius, mass,
// angular_velocity_*, orientation_*), their contact history "contacts" with its own row count.
// Readers look up only the groups their scene needs and ignore others, so adding a species or a
// field does not change format version 1. The version changes only if the meaning or shape of
// an existing dataset does.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace narrows::io {

inline constexpr std::int64_t checkpoint_format_version = 1;
// The largest step a checkpoint name holds (10 digits).
inline constexpr std::int64_t max_checkpoint_step = 9999999999;

// What a checkpoint stores besides the particles.
struct CheckpointInfo {
  std::string scene_text;      // the scene that ran (overrides re-serialised)
  std::string canonical_scene; // its canonical text (empty: not written / not in the file)
  std::int64_t step = 0;
  double time = 0.0;
  std::uint64_t seed = 0;
  int dimensions = 2;
  std::array<double, 3> box{1.0, 1.0, 1.0}; // edge lengths (first `dimensions` used)
  bool walls_y = false;              // box/boundary along y: "none" (walls) instead of "periodic"
  std::uint64_t fluid_particles = 0; // filled by the reader
};

// One species on this rank as structure-of-arrays views. Vector fields have `dim` component
// arrays and are stored as [N][dim]; word and scalar fields are stored as [N].
struct SpeciesFields {
  std::string name;
  int dim = 2;
  std::vector<std::pair<std::string, std::array<std::vector<double> *, 3>>> vectors;
  std::vector<std::pair<std::string, std::vector<std::uint64_t> *>> words;
  std::vector<std::pair<std::string, std::vector<double> *>> scalars;
  std::size_t rows() const;
};

// Whether the checkpoint holds /particles/<species>/<field>/value (collective: every rank
// opens the file), for fields that older checkpoints lack.
bool has_species_field(const std::string &path, const std::string &species,
                       const std::string &field, MPI_Comm comm);

// An engine's own state that is not particles (the kmc engine's running sums over replicas):
// a float64 array at `path` (e.g. "kmc/mean"; its groups are created), shape [values.size()].
// Only rank 0's values are written; other ranks may pass empty vectors.
struct CheckpointArray {
  std::string path;
  std::vector<double> values;
};

// Writes `path` collectively on all ranks of comm: first to `path`.tmp, then (rank 0, after
// the file is closed and synced) renamed to `path`, so a crash never leaves a partial file
// under the final name; if writing fails, the temporary file is removed. Returns the bytes of
// particle data written (all ranks).
double write_checkpoint(const std::string &path, const CheckpointInfo &info,
                        const std::vector<SpeciesFields> &species, MPI_Comm comm,
                        const std::vector<CheckpointArray> &arrays = {});

// Reads and checks the header of a checkpoint (collective). Anything that makes it unusable
// throws input_error with one line: missing file, not HDF5, truncated or damaged, missing
// dataset, wrong format version, row counts of the fluid fields that disagree.
CheckpointInfo read_checkpoint_info(const std::string &path, MPI_Comm comm);

// A CheckpointArray back (every rank reads it); input_error naming the dataset if it is
// missing or not of shape [size].
std::vector<double> read_checkpoint_array(const std::string &path, const std::string &name,
                                          std::size_t size, MPI_Comm comm);

// Whether the checkpoint holds the array `name` (collective), for state that a checkpoint has
// only when its run computed it.
bool has_checkpoint_array(const std::string &path, const std::string &name, MPI_Comm comm);

// Reads and checks /parameters only (collective): for checkpoints without a fluid (lattice
// engines). Same refusals as read_checkpoint_info for the file and the parameters.
CheckpointInfo read_checkpoint_header(const std::string &path, MPI_Comm comm);

// The box edges stored with a species (/particles/<species>/box/edges, checksum verified;
// collective): input_error if missing, of another shape, damaged or not finite and > 0.
std::array<double, 3> read_box_edges(const std::string &path, const std::string &species, int dim,
                                     MPI_Comm comm);

// Rows of a species in the file (its first field).
std::uint64_t species_rows(const std::string &path, const SpeciesFields &species, MPI_Comm comm);

// Reads rows [first, first + n) of every field of `species` on this rank (collective; the
// arrays are resized to n).
void read_species_rows(const std::string &path, SpeciesFields &species, std::uint64_t first,
                       std::uint64_t n, MPI_Comm comm);

// Reads this rank's block of the rows of every field of `species` (collective); the arrays
// are resized. The species must exist in the file (it was checked by read_checkpoint_info for
// the fluid).
void read_species(const std::string &path, SpeciesFields &species, MPI_Comm comm);

// ---- files of a run directory ------------------------------------------------------------

// DIR/checkpoint-<step as 10 digits>.h5
std::string checkpoint_path(const std::string &dir, std::int64_t step);

// The checkpoint `--restart ARG` means: ARG itself if it is a file, else the checkpoint with
// the highest step in the directory ARG (temporary files ignored). input_error if there is
// none.
std::string resolve_restart(const std::string &arg);

// The complete checkpoints of dir (checkpoint-<10 digits>.h5), oldest first.
std::vector<std::string> list_checkpoints(const std::string &dir);

// Removes all but the newest `keep` checkpoints of dir, and leftover temporary files of
// checkpoints that were never completed. Rank 0 only; errors are ignored (it is cleanup).
void prune_checkpoints(const std::string &dir, int keep);

} // namespace narrows::io
