// Engine "lgca": check/info text and the engine of `narrows run` for lattice-gas scenes, and the
// lattice benchmark.
#pragma once

#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/run/engine.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace narrows::lgca {

// The lattice of an FHP scene (engine lgca, model not dhumieres-1d).
FhpParams fhp_params(const scene::Scene &scene);
FhpModel fhp_model(scene::LgcaModel m);

// What `check` / `info` print for a lattice scene.
std::vector<std::string> describe(const scene::Scene &scene, MPI_Comm comm);

// `narrows check|info`: refuses what a run would refuse (parts not available, a decomposition
// the lattice cannot take), then describe()'s lines.
std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm);

// `narrows run`: the engine of an FHP scene (DIR/log.txt, DIR/observables.h5, checkpoints,
// restarts) or of the d'Humieres model (replicas, no checkpoints) for run::drive. Refuses first
// what cannot run (exit code 2).
std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &options,
                                         MPI_Comm comm);

// `narrows bench --lgca N`: FHP-III site updates per second per core on an N x N lattice, on
// one rank and on all ranks of comm (the speedup). Collective; rank 0 prints.
void run_bench(std::ostream &out, int n, int steps, bool json, MPI_Comm comm);

} // namespace narrows::lgca
