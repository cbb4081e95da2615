// Checkpoints of the FHP lattice through the checkpoint layer of io/checkpoint.hpp: the
// lattice is the species "lattice" with one word field "state" holding, column by column
// (x = 0 .. size_x - 1), the site bytes of rows 0 .. size_y - 1 packed eight to a word
// (little-endian: row 8k + j in byte j of word k). A slab of columns is a contiguous block
// of rows, so every rank writes and reads only its own columns, on any rank count.
#pragma once

#include "narrows/engines/lgca/colloid_correlations.hpp"
#include "narrows/engines/lgca/fhp_colloid.hpp"
#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/io/checkpoint.hpp"

#include <array>
#include <string>

namespace narrows::lgca {

// Collective; returns the bytes of lattice data written. `canonical_scene`: the scene's
// canonical text (scene/canonical.hpp), stored for restarts if not empty.
double write_lattice_checkpoint(const std::string &path, const FhpLattice &lattice,
                                const std::string &scene_text,
                                const std::string &canonical_scene = {});

// Fills `lattice` (built from the same scene) with the checkpoint's state and step
// (collective). input_error if the stored lattice does not have the lattice's size.
void read_lattice_checkpoint(const std::string &path, const io::CheckpointInfo &info,
                             FhpLattice &lattice);

// ---- the disc of [colloid] -----------------------------------------------------------------
// Beside the lattice in the same file: /colloid/{momentum [2] int64, omega, position [2],
// angle} and, with the colloid's averages, /colloid/correlations/{layout [6] int64, values}
// (ColloidCorrelations::State). Every dataset carries a `checksum` attribute: io::bytes_hash
// of its bytes, as the small datasets of io/checkpoint.cpp. Rank 0 writes, into the complete
// lattice checkpoint.
void write_colloid_checkpoint(const std::string &path, const FhpColloid &colloid,
                              const ColloidCorrelations *stats);

struct ColloidCheckpoint {
  MomentumUnits momentum{};
  double omega = 0.0, angle = 0.0;
  std::array<double, 2> position{};
  ColloidCorrelations::State correlations; // empty layout: the checkpoint has no averages
};

// The disc's state in checkpoint `path` (every rank reads it; wrap the call in
// run::collectively). input_error with one line naming the file and the dataset if a dataset
// is missing, does not match its checksum (a checkpoint written before the checksums existed
// has none: a warning on stderr, rank 0), or holds what no run can have written, naming the
// first bad row: a number that is not finite, a centre outside the lattice ([0, size_x) x
// [0, size_y sqrt(3)/2)), a held disc away from colloid.position or turned, averages with a
// negative count or layout entry.
ColloidCheckpoint read_colloid_checkpoint(const std::string &path, const FhpLattice &lattice,
                                          const ColloidParams &params);

} // namespace narrows::lgca
