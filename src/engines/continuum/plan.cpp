// Grid, time step and initial data of a conservation-law scene (see continuum/plan.hpp).
#include "narrows/engines/continuum/plan.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
    // Integral of the piecewise-linear interpolant through the points x_k = k h. The cell
    // edges advance monotonically, so the whole intervals are summed once (prefix sums):
    // linear in cells + values (a profile of 1e7 values on 1e8 cells took hours when every
    // edge summed from 0).
    const std::size_t K = m.profile.size() - 1;
    const double h = m.length / static_cast<double>(K);
    std::vector<double> whole(K + 1, 0.0); // integral from 0 to x_k
    for (std::size_t k = 0; k < K; ++k)
      whole[k + 1] = whole[k] + 0.5 * h * (m.profile[k] + m.profile[k + 1]);
    const auto integral = [&](double x) { // of the interpolant from 0 to x
      const std::size_t full = std::min<std::size_t>(K, static_cast<std::size_t>(x / h));
      double s = whole[full];
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

SampleSteps sample_steps(const scene::Continuum &m, std::int64_t points, double dt_max,
                         const std::string &why) {
  const auto samples = static_cast<double>(m.samples);
  const double per = std::ceil(m.time / samples / dt_max);
  char line[600];
  if (!(per * samples <= 9e9)) {
    std::snprintf(line, sizeof line,
                  "continuum.time = %.6g needs %.3g steps of dt <= %.3g (%s); allowed: at most "
                  "9e9 steps",
                  m.time, per * samples, dt_max, why.c_str());
    throw input_error(line);
  }
  SampleSteps out;
  out.per_sample = std::max<std::int64_t>(1, static_cast<std::int64_t>(per));
  out.steps = out.per_sample * m.samples;
  out.dt = m.time / static_cast<double>(out.steps);
  const double work = static_cast<double>(out.steps) * static_cast<double>(points);
  if (!(work <= m.max_work)) {
    std::snprintf(line, sizeof line,
                  "continuum.max_work: %.3g point-steps (%lld points x %lld steps of dt %.3g: "
                  "%s); allowed: at most continuum.max_work = %.3g (raise continuum.max_work to "
                  "run it: about 1e7 point-steps take a second)",
                  work, static_cast<long long>(points), static_cast<long long>(out.steps), out.dt,
                  why.c_str(), m.max_work);
    throw input_error(line);
  }
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
  char why[300];
  std::snprintf(why, sizeof why,
                "CFL %g with max|J'| = %.3g, continuum.diffusion = %.3g on cells of dx = %.3g; "
                "fewer continuum.cells or a smaller continuum.diffusion lengthen it",
                m.cfl, p.max_speed, m.diffusion, p.grid.dx);
  const SampleSteps steps = sample_steps(m, m.cells, dt_max, why);
  p.per_sample = steps.per_sample;
  p.steps = steps.steps;
  p.dt = steps.dt;
  p.courant = p.max_speed * p.dt / p.grid.dx;
  p.diffusion_number = m.diffusion * p.dt / (p.grid.dx * p.grid.dx);
  return p;
}

} // namespace narrows::continuum
