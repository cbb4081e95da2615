// Checkpoints of the FHP lattice through the checkpoint layer of io/checkpoint.hpp: the
// lattice is the species "lattice" with one word field "state" holding, column by column
// (x = 0 .. size_x - 1), the site bytes of rows 0 .. size_y - 1 packed eight to a word
// (little-endian: row 8k + j in byte j of word k). A slab of columns is a contiguous block
// of rows, so every rank writes and reads only its own columns, on any rank count.
#pragma once

#include "narrows/io/checkpoint.hpp"
#include "narrows/lattice/fhp_lattice.hpp"

#include <string>

namespace narrows::lattice {

// Collective; returns the bytes of lattice data written. `canonical_scene`: the scene's
// canonical text (scene/canonical.hpp), stored for restarts if not empty.
double write_lattice_checkpoint(const std::string &path, const FhpLattice &lattice,
                                const std::string &scene_text,
                                const std::string &canonical_scene = {});

// Fills `lattice` (built from the same scene) with the checkpoint's state and step
// (collective). input_error if the stored lattice does not have the lattice's size.
void read_lattice_checkpoint(const std::string &path, const io::CheckpointInfo &info,
                             FhpLattice &lattice);

} // namespace narrows::lattice
