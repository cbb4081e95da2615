// Engine "continuum" (model "conservation-law"; "jamming" and "segregation" are dispatched to
// jamming_driver.hpp and segregation_driver.hpp):
// the run/check/info commands over the run shell (run/shell.hpp): output folder, log,
// observables (density, shock_position), checkpoints of the cell averages and bitwise restarts.
#pragma once

#include "narrows/run/shell.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>
#include <vector>

namespace narrows::continuum {

// What `check` / `info` and the run log print: the model, the flux, grid, boundary, initial
// data, the scheme and its time step.
std::vector<std::string> describe(const scene::Scene &scene);

// `narrows run` for a continuum scene. The 1D grid is small: every rank advances the same
// cells (no decomposition; more ranks do not make it faster) and rank 0 writes.
void run_scene(const scene::Scene &scene, const run::Options &options, MPI_Comm comm);

// `narrows check|info|run` for a continuum scene (called by main once the scene is parsed).
int command(const scene::Scene &scene, bool check, bool info, const run::Options &options,
            MPI_Comm comm);

} // namespace narrows::continuum
