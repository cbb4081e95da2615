// `narrows run`: drives a simulation from a validated scene, with output, progress, checks.
#pragma once

#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>

namespace narrows::engine {

struct RunOptions {
  std::string out_dir; // overrides scene.output.dir when not empty
  std::string restart; // checkpoint file or directory to continue from (empty: start fresh)
};

// Runs the scene to run.steps. Writes DIR/log.txt and DIR/observables.h5 (rank 0) and ends
// with the "Loop time" summary line. Throws narrows::Error on bad input or broken invariants.
void run_scene(const scene::Scene &scene, const RunOptions &options, MPI_Comm comm);

} // namespace narrows::engine
