// Grid, time step and initial data of a conservation-law scene (see continuum/plan.hpp).
#include "narrows/engines/continuum/plan.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace narrows::continuum {

std::vector<double> initial_cells(const scene::Continuum &m) {
  const std::size_t n = static_cast<std::size_t>(m.cells);
  const double dx = m.length / static_cast<double>(m.cells);
  std::vector<double> u(n);
  switch (m.initial) {
  case scene::ContinuumInitial::riemann:
    for (std::size_t i = 0; i < n; ++i) {
      const double a = static_cast<double>(i) * dx, b = a + dx;
      const double left_part = std::clamp((m.position - a) / dx, 0.0, 1.0);
      u[i] = left_part * m.left + (1.0 - left_part) * m.right;
      if (b <= m.position)
        u[i] = m.left; // exact, not a rounded mixture
      else if (a >= m.position)
        u[i] = m.right;
    }
    break;
  case scene::ContinuumInitial::profile: {
    // Integral of the piecewise-linear interpolant through the points x_k = k h.
    const std::size_t K = m.profile.size() - 1;
    const double h = m.length / static_cast<double>(K);
    const auto integral = [&](double x) { // of the interpolant from 0 to x
      double s = 0.0;
      const std::size_t full = std::min<std::size_t>(K, static_cast<std::size_t>(x / h));
      for (std::size_t k = 0; k < full; ++k)
        s += 0.5 * h * (m.profile[k] + m.profile[k + 1]);
      if (full < K) {
        const double t = x - static_cast<double>(full) * h;
        const double v = m.profile[full] + (m.profile[full + 1] - m.profile[full]) * t / h;
        s += 0.5 * t * (m.profile[full] + v);
      }
      return s;
    };
    double prev = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double next = integral(std::min(m.length, static_cast<double>(i + 1) * dx));
      u[i] = (next - prev) / dx;
      prev = next;
    }
    break;
  }
  case scene::ContinuumInitial::cells:
    u = m.profile;
    break;
  case scene::ContinuumInitial::random: // model jamming only (jamming_plan.cpp)
  case scene::ContinuumInitial::eigenmode:
    break;
  case scene::ContinuumInitial::sine: {
    const double k = 2.0 * std::numbers::pi / m.length;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = static_cast<double>(i) * dx, b = a + dx;
      u[i] = m.mean + m.amplitude * (std::cos(k * a) - std::cos(k * b)) / (k * dx);
    }
    break;
  }
  }
  return u;
}

std::vector<double> cell_centres(const Grid &grid) {
  std::vector<double> x(static_cast<std::size_t>(grid.cells));
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = (static_cast<double>(i) + 0.5) * grid.dx;
  return x;
}

SampleSteps sample_steps(double time, std::int64_t samples, double dt_max) {
  const double per = std::ceil(time / static_cast<double>(samples) / dt_max);
  if (!(per * static_cast<double>(samples) <= 9e9))
    throw input_error("continuum: " + std::to_string(per * static_cast<double>(samples)) +
                      " steps (continuum.time / the CFL time step); allowed: at most 9e9 "
                      "(fewer continuum.cells, a shorter continuum.time)");
  SampleSteps out;
  out.per_sample = std::max<std::int64_t>(1, static_cast<std::int64_t>(per));
  out.steps = out.per_sample * samples;
  out.dt = time / static_cast<double>(out.steps);
  return out;
}

Plan make_plan(const scene::Continuum &m) {
  Plan p;
  p.grid.cells = m.cells;
  p.grid.dx = m.length / static_cast<double>(m.cells);
  p.grid.periodic = m.boundary == scene::ContinuumBoundary::periodic;
  p.grid.left = m.reservoirs[0];
  p.grid.right = m.reservoirs[1];
  const std::vector<double> u = initial_cells(m);
  p.lo = *std::min_element(u.begin(), u.end());
  p.hi = *std::max_element(u.begin(), u.end());
  if (!p.grid.periodic) {
    p.lo = std::min({p.lo, p.grid.left, p.grid.right});
    p.hi = std::max({p.hi, p.grid.left, p.grid.right});
  }
  const Flux flux(m);
  p.max_speed = flux.max_speed(p.lo, p.hi);
  const double dt_max = stable_dt(p.max_speed, p.grid.dx, m.diffusion, m.cfl);
  const SampleSteps steps = sample_steps(m.time, m.samples, dt_max);
  p.per_sample = steps.per_sample;
  p.steps = steps.steps;
  p.dt = steps.dt;
  p.courant = p.max_speed * p.dt / p.grid.dx;
  p.diffusion_number = m.diffusion * p.dt / (p.grid.dx * p.grid.dx);
  return p;
}

} // namespace narrows::continuum
