// Engine "continuum" (model "conservation-law"; "jamming" and "segregation" are dispatched to
// jamming_driver.hpp and segregation_driver.hpp):
// the check/info text and the engine of the run loop (run/drive.hpp): observables (density,
// shock_position), checkpoints of the cell averages and bitwise restarts.
#pragma once

#include "narrows/run/engine.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

namespace narrows::continuum {

// What `check` / `info` and the run log print: the model, the flux, grid, boundary, initial
// data, the scheme and its time step.
std::vector<std::string> describe(const scene::Scene &scene);

// `narrows check|info`: describe()'s lines (the plan refuses what cannot run).
std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm);

// `narrows run`: the engine of a continuum scene for run::drive (continuum/field_run.hpp). The
// 1D grid is small: every rank advances the same cells (no decomposition; more ranks do not
// make it faster) and rank 0 writes.
std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &options,
                                         MPI_Comm comm);

} // namespace narrows::continuum
