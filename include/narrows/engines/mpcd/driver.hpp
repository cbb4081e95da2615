// The mpcd engine for the command line: what `check` / `info` print, and the engine that
// `narrows run` drives (run/drive.hpp) with observables, trajectory, checkpoints and invariant
// checks.
#pragma once

#include "narrows/run/engine.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

namespace narrows::mpcd {

// `narrows check|info`: refuses what a run would refuse (colloid placement, check_runnable,
// the decomposition), then the pipeline, sizes and numbers (mpcd/info.hpp) and the regime's
// warnings ("warning: ..."). Collective; the lines are rank 0's to print.
std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm);

// `narrows run`: refuses a decomposition the box cannot take, then the engine that runs the
// scene to run.steps, writing DIR/log.txt and DIR/observables.h5 (rank 0) and checkpoints.
std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &options,
                                         MPI_Comm comm);

} // namespace narrows::mpcd
