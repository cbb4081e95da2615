// Engine "continuum", model "segregation": check/info lines and the run over the run shell
// (observables density = phi_i per kind, evolution = Delta(t) of eq 5.31, steady_density = the
// steady profile; checkpoints of the fractions, bitwise restarts).
#pragma once

#include "narrows/run/shell.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>
#include <vector>

namespace narrows::continuum {

// The model, its kinds (coupling matrix A, Peclet numbers), viscosity and shear rate, grid, the
// steady profile (centre and wall values, the thesis' migration-to-diffusion ratio at the wall),
// the scheme and its time step.
std::vector<std::string> describe_segregation(const scene::Scene &scene);

// Every rank advances the same cells (1D, no decomposition) and rank 0 writes.
void run_segregation(const scene::Scene &scene, const run::Options &options, MPI_Comm comm);

} // namespace narrows::continuum
