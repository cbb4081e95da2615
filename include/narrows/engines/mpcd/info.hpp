// What a scene will do, before it runs: pipeline, sizes, and the dimensionless numbers.
#pragma once

#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>
#include <vector>

namespace narrows::mpcd {

// Lines describing the run: pipeline of stages, particle count, memory estimate, mean free
// path, theory viscosity and Sc, and Ma/Re when a body force is set; the pipeline as it runs
// on the ranks of comm (no messages are sent).
// Refuses first what cannot run (check_runnable).
std::vector<std::string> describe_scene(const scene::Scene &scene, MPI_Comm comm);

class MpcdSimulation;
// The same lines for a simulation already built (describe_scene builds one without its state):
// the pipeline is its stage list as it is now, the list the step runs.
std::vector<std::string> describe_simulation(const MpcdSimulation &sim);

// Refuses (input_error, one line) a scene that cannot run: a mean free path beyond 1e6 cells,
// zero or more than 1e15 fluid particles, a memory estimate above the machine's memory per
// rank (physical memory / ranks on the node), colloids whose thermal motion per MD sub-step
// exceeds their radius.
void check_runnable(const scene::Scene &scene, MPI_Comm comm);

// Places the scene's colloids as a run would (colloid_placement.hpp), so that `check` and a run
// refuse what cannot be placed (overlapping given positions, no free place) before anything is
// written: a bad-input error prefixed with the scene file.
void check_colloid_placement(const scene::Scene &scene);

// Warnings about the physical regime (Ma > 0.2, unbounded acceleration...).
std::vector<std::string> regime_warnings(const scene::Scene &scene);

} // namespace narrows::mpcd
