// The resolved numerics of a jamming scene: grid points, time step, steps and sampling, and the
// initial fields phi, v at the points.
#pragma once

#include "narrows/scene/scene.hpp"

#include <cstdint>
#include <vector>

namespace narrows::continuum {

struct JammingPlan {
  std::int64_t points = 0;
  double dx = 1.0;             // length / points
  double speed_bound = 0.0;    // largest of |v| initially and v_ss on [0, 1] (max principle)
  double dt = 0.0;             // continuum.time / steps
  std::int64_t steps = 0;      // steps of the whole run
  std::int64_t per_sample = 0; // steps between samples
  double courant = 0.0;        // speed_bound dt / dx
};

// dt is the largest step <= cfl dx / speed_bound that puts every sample time on a step.
JammingPlan make_jamming_plan(const scene::Continuum &model);

// phi and v at the points x_i = i dx: sine or random phi about the mean, or the given values;
// v = v_ss(phi) at each point unless given (kind "cells" with `velocity`).
void jamming_initial(const scene::Continuum &model, std::vector<double> &phi,
                     std::vector<double> &v);

// x_i = i dx (the bins of the density and velocity observables).
std::vector<double> jamming_points(const JammingPlan &plan);

} // namespace narrows::continuum
