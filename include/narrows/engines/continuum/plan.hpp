// The resolved numerics of a conservation-law scene: grid, time step from the CFL condition,
// steps, sampling, and the initial cell averages.
#pragma once

#include "narrows/engines/continuum/scheme.hpp"
#include "narrows/scene/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace narrows::continuum {

struct Plan {
  Grid grid;
  double lo = 0.0, hi = 0.0;     // range of the initial and reservoir densities
  double max_speed = 0.0;        // max |J'| over [lo, hi]
  double dt = 0.0;               // time step: continuum.time / steps
  std::int64_t steps = 0;        // steps of the whole run
  std::int64_t per_sample = 0;   // steps between samples (steps = samples * per_sample)
  double courant = 0.0;          // max|J'| dt / dx
  double diffusion_number = 0.0; // D dt / dx^2
};

// The steps of a run of `time` with `samples` samples at a step no longer than dt_max: the
// largest dt <= dt_max that puts every sample time k time / samples on a step. Shared by the
// continuum models. Refused (input_error, one line naming the key): beyond 9e9 steps, or more
// than continuum.max_work point-steps (`points` grid points a step). `why` says what sets
// dt_max and what would lengthen it ("speed bound 1e+300 of continuum.initial.velocity; slower
// velocities"), for the message.
struct SampleSteps {
  double dt = 0.0;
  std::int64_t steps = 0, per_sample = 0;
};
SampleSteps sample_steps(const scene::Continuum &m, std::int64_t points, double dt_max,
                         const std::string &why);

// dt is the largest step <= stable_dt (scheme.hpp) that puts every sample time
// k continuum.time / continuum.samples on a step, so samples are exact in time and the run
// ends at continuum.time.
Plan make_plan(const scene::Continuum &model);

// Cell averages of the initial data (riemann: the cut cell takes the weighted mean; profile:
// the piecewise-linear interpolant averaged exactly; sine: exact averages; cells: as given).
std::vector<double> initial_cells(const scene::Continuum &model);

// Cell centres (the bins of the density observable).
std::vector<double> cell_centres(const Grid &grid);

} // namespace narrows::continuum
