// What a scene will do, before it runs: pipeline, sizes, and the dimensionless numbers.
#pragma once

#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <string>
#include <vector>

namespace narrows::engine {

// Lines describing the run: pipeline of stages, particle count, memory estimate, mean free
// path, theory viscosity and Sc, and Ma/Re when a body force is set; the pipeline as it runs
// on the ranks of comm (no messages are sent).
std::vector<std::string> describe_scene(const scene::Scene &scene, MPI_Comm comm);

// Places the scene's colloids as a run would (colloids/placement.hpp), so that `check` and a run
// refuse what cannot be placed (overlapping given positions, no free place) before anything is
// written: a bad-input error prefixed with the scene file.
void check_colloid_placement(const scene::Scene &scene);

// Warnings about the physical regime (Ma > 0.2, unbounded acceleration...).
std::vector<std::string> regime_warnings(const scene::Scene &scene);

} // namespace narrows::engine
