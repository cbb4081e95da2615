// Engine "continuum", model "jamming": check/info lines and the model of the continuum engine
// (observables density = phi and velocity = v, checkpoints of both, bitwise restarts).
#pragma once

#include "narrows/engines/continuum/field_run.hpp"
#include "narrows/scene/scene.hpp"

#include <memory>
#include <string>
#include <vector>

namespace narrows::continuum {

// The model, v_ss fit, grid, initial data, the linear stability of the mean state (unstable
// band and fastest mode, eq 6.11), the scheme and its time step.
std::vector<std::string> describe_jamming(const scene::Scene &scene);

// The model for the continuum engine (continuum/field_run.hpp): fields phi and v.
std::unique_ptr<FieldModel> make_jamming(const scene::Scene &scene);

} // namespace narrows::continuum
