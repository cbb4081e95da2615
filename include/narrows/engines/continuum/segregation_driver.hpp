// Engine "continuum", model "segregation": check/info lines and the model of the continuum engine
// (observables density = phi_i per kind, evolution = Delta(t) of eq 5.31, steady_density = the
// steady profile; checkpoints of the fractions, bitwise restarts).
#pragma once

#include "narrows/engines/continuum/field_run.hpp"
#include "narrows/scene/scene.hpp"

#include <memory>
#include <string>
#include <vector>

namespace narrows::continuum {

// The model, its kinds (coupling matrix A, Peclet numbers), viscosity and shear rate, grid, the
// steady profile (centre and wall values, the thesis' migration-to-diffusion ratio at the wall),
// the scheme and its time step.
std::vector<std::string> describe_segregation(const scene::Scene &scene);

// The model for the continuum engine (continuum/field_run.hpp): the fraction of every kind.
std::unique_ptr<FieldModel> make_segregation(const scene::Scene &scene);

} // namespace narrows::continuum
