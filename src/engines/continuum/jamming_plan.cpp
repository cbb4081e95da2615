// Time step and initial fields of a jamming scene (see continuum/jamming_plan.hpp).
#include "narrows/engines/continuum/jamming_plan.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/continuum/jamming_model.hpp"
#include "narrows/engines/continuum/jamming_stability.hpp"
#include "narrows/engines/continuum/plan.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

namespace narrows::continuum {

void jamming_initial(const scene::Continuum &m, std::vector<double> &phi, std::vector<double> &v) {
  const std::size_t n = static_cast<std::size_t>(m.cells);
  const double dx = m.length / static_cast<double>(m.cells);
  phi.assign(n, m.mean);
  switch (m.initial) {
  case scene::ContinuumInitial::sine: {
    const double k = 2.0 * std::numbers::pi * static_cast<double>(m.mode) / m.length;
    for (std::size_t i = 0; i < n; ++i)
      phi[i] = m.mean + m.amplitude * std::sin(k * static_cast<double>(i) * dx);
    break;
  }
  case scene::ContinuumInitial::random:
    for (std::size_t i = 0; i < n; ++i) {
      const rng::Block b = rng::draw(m.seed, rng::Purpose::continuum_initial, 0, i);
      phi[i] = m.mean + m.amplitude * (2.0 * rng::uniform53(b[0], b[1]) - 1.0);
    }
    break;
  case scene::ContinuumInitial::eigenmode: {
    // Each mode on the eigenvector of its eigenvalue of larger real part (eq 6.10-6.11):
    // phi_n = a e^(i theta), v_n = r phi_n with r = -(lambda + i k v0 + D k^2) / (i k phi0).
    const JammingModel model(m);
    const double v0 = model.vss(m.mean), D = model.diffusion();
    v.assign(n, v0);
    for (std::size_t j = 0; j < m.modes.size(); ++j) {
      const double k = 2.0 * std::numbers::pi * static_cast<double>(m.modes[j]) / m.length;
      const std::complex<double> lambda = growth_rate(model, m.mean, k);
      const std::complex<double> r = -(lambda + std::complex<double>(D * k * k, k * v0)) /
                                     std::complex<double>(0.0, k * m.mean);
      const rng::Block b = rng::draw(m.seed, rng::Purpose::continuum_initial, 1, j);
      const double theta = 2.0 * std::numbers::pi * rng::uniform53(b[0], b[1]);
      for (std::size_t i = 0; i < n; ++i) {
        const std::complex<double> e =
            std::polar(m.amplitude, k * static_cast<double>(i) * dx + theta);
        phi[i] += e.real();
        v[i] += (r * e).real();
      }
    }
    return;
  }
  default: // cells
    phi = m.profile;
    break;
  }
  const JammingModel model(m);
  if (!m.velocity.empty()) {
    v = m.velocity;
    return;
  }
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = model.vss(phi[i]);
}

std::vector<double> jamming_points(const JammingPlan &plan) {
  std::vector<double> x(static_cast<std::size_t>(plan.points));
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = static_cast<double>(i) * plan.dx;
  return x;
}

JammingPlan make_jamming_plan(const scene::Continuum &m) {
  JammingPlan p;
  p.points = m.cells;
  p.dx = m.length / static_cast<double>(m.cells);
  std::vector<double> phi, v;
  jamming_initial(m, phi, v);
  const JammingModel model(m);
  p.speed_bound = std::max(model.vss(0.0), model.vss(1.0));
  const double vss_bound = p.speed_bound;
  for (double x : v)
    p.speed_bound = std::max(p.speed_bound, std::abs(x));
  const double dt_max = m.cfl * p.dx / p.speed_bound;
  char why[300];
  if (!m.velocity.empty() && p.speed_bound > vss_bound)
    std::snprintf(why, sizeof why,
                  "CFL %g with the speed bound %.3g of continuum.initial.velocity on points %.3g "
                  "apart; slower continuum.initial.velocity lengthen it",
                  m.cfl, p.speed_bound, p.dx);
  else
    std::snprintf(why, sizeof why,
                  "CFL %g with the speed bound %.3g on points %.3g apart; fewer continuum.cells "
                  "lengthen it",
                  m.cfl, p.speed_bound, p.dx);
  const SampleSteps steps = sample_steps(m, m.cells, dt_max, why);
  p.per_sample = steps.per_sample;
  p.steps = steps.steps;
  p.dt = steps.dt;
  p.courant = p.speed_bound * p.dt / p.dx;
  return p;
}

} // namespace narrows::continuum
