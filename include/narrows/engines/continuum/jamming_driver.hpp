// Engine "continuum", model "jamming": check/info lines and the run over the run shell
// (observables density = phi and velocity = v, checkpoints of both, bitwise restarts).
#pragma once

#include "narrows/run/shell.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>
#include <vector>

namespace narrows::continuum {

// The model, v_ss fit, grid, initial data, the linear stability of the mean state (unstable
// band and fastest mode, eq 6.11), the scheme and its time step.
std::vector<std::string> describe_jamming(const scene::Scene &scene);

// Every rank advances the same points (1D, no decomposition) and rank 0 writes.
void run_jamming(const scene::Scene &scene, const run::Options &options, MPI_Comm comm);

} // namespace narrows::continuum
