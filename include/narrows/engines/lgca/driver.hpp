// Engine "lgca": the check/info/run commands for lattice-gas scenes and the lattice benchmark.
#pragma once

#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/run/shell.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <ostream>
#include <string>
#include <vector>

namespace narrows::lgca {

// The lattice of an FHP scene (engine lgca, model not dhumieres-1d).
FhpParams fhp_params(const scene::Scene &scene);
FhpModel fhp_model(scene::LgcaModel m);

// What `check` / `info` print for a lattice scene.
std::vector<std::string> describe(const scene::Scene &scene, MPI_Comm comm);

// `narrows run` for an FHP scene: DIR/log.txt, DIR/observables.h5, checkpoints, the "Loop
// time" line, in the run shell (run/shell.hpp).
void run_scene(const scene::Scene &scene, const run::Options &options, MPI_Comm comm);

// `narrows check|info|run` for a lattice scene (called by main once the scene is parsed).
// Parts not available in this version ([tagged], dhumieres-1d) are refused with exit code 2.
int command(const scene::Scene &scene, bool check, bool info, const run::Options &options,
            MPI_Comm comm);

// `narrows bench --lgca N`: FHP-III site updates per second per core on an N x N lattice, on
// one rank and on all ranks of comm (the speedup). Collective; rank 0 prints.
void run_bench(std::ostream &out, int n, int steps, bool json, MPI_Comm comm);

} // namespace narrows::lgca
