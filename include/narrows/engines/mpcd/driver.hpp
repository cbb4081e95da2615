// `narrows run` for the mpcd engine: drives a simulation from a validated scene in the run
// shell (run/shell.hpp), with observables, trajectory, checkpoints and invariant checks.
#pragma once

#include "narrows/run/shell.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

namespace narrows::mpcd {

// Runs the scene to run.steps. Writes DIR/log.txt and DIR/observables.h5 (rank 0) and ends
// with the "Loop time" summary line. Throws narrows::Error on bad input or broken invariants.
void run_scene(const scene::Scene &scene, const run::Options &options, MPI_Comm comm);

} // namespace narrows::mpcd
