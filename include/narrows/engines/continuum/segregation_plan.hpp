// The resolved numerics of a segregation scene: the steady profile (by shooting), the time step
// from the largest diffusive and drift rates of the uniform start and the steady state, steps
// and sampling.
#pragma once

#include "narrows/engines/continuum/segregation_steady.hpp"
#include "narrows/scene/scene.hpp"

#include <cstdint>

namespace narrows::continuum {

struct SegregationPlan {
  double h = 0.0;              // cell width 2w / cells
  double diffusive = 0.0;      // largest row sum of |M| at the faces (start, steady)
  double drift = 0.0;          // largest drift speed there
  double dt = 0.0;             // continuum.time / steps
  std::int64_t steps = 0;      // steps of the whole run
  std::int64_t per_sample = 0; // steps between samples
  double number = 0.0;         // dt (diffusive / h^2 + drift / h), <= continuum.cfl
  SteadyProfile steady;        // the steady state (steady.ok false: none found)
};

// dt is the largest step with dt (diffusive / h^2 + drift / h) <= cfl that puts every sample on
// a step. The steady profile is integrated in 8 steps per cell (at least 4096).
SegregationPlan make_segregation_plan(const scene::Continuum &model);

} // namespace narrows::continuum
