// Time step and steady state of a segregation scene (see continuum/segregation_plan.hpp).
#include "narrows/engines/continuum/segregation_plan.hpp"

#include "narrows/engines/continuum/plan.hpp"
#include "narrows/engines/continuum/segregation_solver.hpp"

#include <algorithm>
#include <cstdio>

namespace narrows::continuum {

SegregationPlan make_segregation_plan(const scene::Continuum &m) {
  SegregationPlan p;
  const SegregationModel model(m.segregation);
  const std::size_t n = model.kinds(), cells = static_cast<std::size_t>(m.cells);
  const SegregationSolver grid(model, cells);
  p.h = grid.cell();
  p.steady = steady_profile(model, std::max<std::size_t>(8 * cells, 4096));
  std::vector<double> start(grid.faces().size() * n);
  for (std::size_t f = 0; f < grid.faces().size(); ++f)
    for (std::size_t i = 0; i < n; ++i)
      start[f * n + i] = m.segregation.kinds[i].fraction;
  double worst = 0.0;
  const auto bound = [&](const std::vector<double> &phi) {
    for (std::size_t f = 0; f < grid.faces().size(); ++f) {
      double diffusive = 0.0, drift = 0.0;
      model.rates(&phi[f * n], grid.faces()[f], diffusive, drift);
      p.diffusive = std::max(p.diffusive, diffusive);
      p.drift = std::max(p.drift, drift);
      worst = std::max(worst, diffusive / (p.h * p.h) + drift / p.h);
    }
  };
  bound(start);
  if (p.steady.ok)
    bound(steady_at(p.steady, grid.faces()));
  char why[300];
  std::snprintf(why, sizeof why,
                "continuum.cfl %g with the largest rate %.3g on cells of h = %.3g; fewer "
                "continuum.cells lengthen it",
                m.cfl, worst, p.h);
  const SampleSteps steps = sample_steps(m, m.cells, m.cfl / worst, why);
  p.per_sample = steps.per_sample;
  p.steps = steps.steps;
  p.dt = steps.dt;
  p.number = p.dt * worst;
  return p;
}

} // namespace narrows::continuum
