// Engine "continuum": describe, run (over the run shell), check/info (see continuum/driver.hpp).
#include "narrows/engines/continuum/driver.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/continuum/exact.hpp"
#include "narrows/engines/continuum/field_run.hpp"
#include "narrows/engines/continuum/flux.hpp"
#include "narrows/engines/continuum/jamming_driver.hpp"
#include "narrows/engines/continuum/plan.hpp"
#include "narrows/engines/continuum/scheme.hpp"
#include "narrows/engines/continuum/segregation_driver.hpp"
#include "narrows/engines/continuum/shock.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/run/collective.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

namespace narrows::continuum {

namespace {

// The Riemann problem of the scene's initial data (riemann kind, convex or concave flux).
bool riemann_of(const scene::Continuum &m, const Flux &flux, Riemann &out) {
  if (m.initial != scene::ContinuumInitial::riemann)
    return false;
  try {
    out = riemann(flux, m.left, m.right);
  } catch (const std::invalid_argument &) {
    return false;
  }
  return true;
}

} // namespace

std::vector<std::string> describe(const scene::Scene &scene) {
  if (scene.continuum->model == scene::ContinuumModel::jamming)
    return describe_jamming(scene);
  if (scene.continuum->model == scene::ContinuumModel::segregation)
    return describe_segregation(scene);
  const scene::Continuum &m = *scene.continuum;
  const Flux flux(m);
  const Plan p = plan_of(scene, make_plan);
  std::vector<std::string> out;
  out.push_back("engine continuum: conservation law rho_t + J(rho)_x = D rho_xx in 1D, D = " +
                format("%g", m.diffusion));
  out.push_back("flux: " + flux.describe());
  out.push_back("grid: " + std::to_string(m.cells) + " cells of dx = " + format("%g", p.grid.dx) +
                " on [0, " + format("%g", m.length) + "], " +
                (p.grid.periodic ? std::string("periodic")
                                 : "open: reservoirs held at " +
                                       format("%g left, %g right", p.grid.left, p.grid.right)));
  switch (m.initial) {
  case scene::ContinuumInitial::riemann:
    out.push_back("initial: Riemann problem " +
                  format("%g | %g at x = %g", m.left, m.right, m.position));
    break;
  case scene::ContinuumInitial::profile:
    out.push_back("initial: profile of " + std::to_string(m.profile.size()) +
                  " values, piecewise linear, cell averages");
    break;
  case scene::ContinuumInitial::cells:
    out.push_back("initial: the given cell averages");
    break;
  case scene::ContinuumInitial::random: // model jamming only (jamming_driver.cpp)
    break;
  case scene::ContinuumInitial::sine:
    out.push_back("initial: " + format("%g + %g sin(2 pi x / %g)", m.mean, m.amplitude, m.length));
    break;
  }
  Riemann rp;
  if (riemann_of(m, flux, rp)) {
    if (rp.shock)
      out.push_back("exact: a shock at the Rankine-Hugoniot speed " + format("%.6g", rp.speed));
    else if (m.left != m.right)
      out.push_back("exact: a rarefaction fan, x/t from " +
                    format("%.6g to %.6g", rp.fan_lo, rp.fan_hi));
  }
  out.push_back(std::string("scheme: finite volumes, MUSCL with the ") +
                (m.limiter == scene::ContinuumLimiter::mc ? "monotonised central" : "minmod") +
                " limiter, Rusanov (local Lax-Friedrichs) flux, central diffusion, SSP-RK2 "
                "(second order where smooth)");
  out.push_back(
      "time step: dt = " +
      format("%.6g (CFL %g: max|J'| = %.6g over [%g, ", p.dt, m.cfl, p.max_speed, p.lo) +
      format("%g]; Courant number %.4g, D dt/dx^2 = %.4g)", p.hi, p.courant, p.diffusion_number));
  out.push_back("time: " + format("%g", m.time) + " in " + std::to_string(p.steps) + " steps; " +
                std::to_string(m.samples) + " samples (every " + std::to_string(p.per_sample) +
                " steps) and t = 0");
  out.push_back("ranks: every rank advances the same cells (no decomposition); memory about " +
                format("%.3g MiB", 7.0 * 8.0 * static_cast<double>(m.cells) / 1048576.0));
  return out;
}

void run_scene(const scene::Scene &scene, const run::Options &options, MPI_Comm comm) {
  if (scene.continuum->model == scene::ContinuumModel::jamming) {
    run_jamming(scene, options, comm);
    return;
  }
  if (scene.continuum->model == scene::ContinuumModel::segregation) {
    run_segregation(scene, options, comm);
    return;
  }
  const scene::Continuum &m = *scene.continuum;
  const Plan p = plan_of(scene, make_plan);
  const Flux flux(m);
  std::vector<double> u = initial_cells(m);
  Scheme scheme(flux, p.grid, m.diffusion, m.limiter);
  const std::vector<double> bins = cell_centres(p.grid);
  std::vector<double> shock_t, shock_x;

  FieldModel model;
  model.dt = p.dt;
  model.steps = p.steps;
  model.per_sample = p.per_sample;
  model.points = u.size();
  model.lines = describe(scene);
  model.fields = {{"density", &u}};
  model.step = [&](double dt) { scheme.step(u, dt); };
  model.check = [&](std::int64_t step) {
    for (std::size_t i = 0; i < u.size(); ++i)
      if (!std::isfinite(u[i]))
        throw invariant_error(scene.file + ": density of cell " + std::to_string(i) +
                              " is not finite at step " + std::to_string(step) +
                              "; the scheme is unstable (report it)");
  };
  model.sample = [&](io::ObservablesWriter *writer, std::int64_t s, double t) {
    const double x = shock_position(u, p.grid.dx, p.grid.periodic);
    shock_t.push_back(t);
    shock_x.push_back(x);
    if (writer == nullptr)
      return;
    if (wants(scene, "density"))
      writer->append_profile("density", s, t, bins, u, 1);
    if (wants(scene, "shock_position"))
      writer->append_scalar("shock_position", s, t, x);
  };
  model.summary = [&](run::Log &log, std::int64_t step) {
    Riemann rp;
    if (shock_t.size() >= 3 && riemann_of(m, flux, rp) && rp.shock) {
      // Speed over the second half of this run's samples (the profile has settled by then).
      const std::size_t a = shock_t.size() / 2, b = shock_t.size() - 1;
      const double v = (shock_x[b] - shock_x[a]) / (shock_t[b] - shock_t[a]);
      log.line(format("shock: at x = %.6g at t = %.6g, speed %.6g (Rankine-Hugoniot %.6g)",
                      shock_x[b], shock_t[b], v, rp.speed));
    }
    double mass = 0.0;
    for (const double x : u)
      mass += x;
    log.line(format("total density (mass) at t = %.6g: %.12g", static_cast<double>(step) * p.dt,
                    mass * p.grid.dx));
  };
  run_fields(scene, options, comm, model);
}

int command(const scene::Scene &scene, bool check, bool info, const run::Options &options,
            MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (check || info) {
    const auto lines = describe(scene);
    if (rank == 0) {
      if (check)
        std::cout << scene.file << ": scene is valid\n";
      for (const auto &line : lines)
        std::cout << line << '\n';
    }
    return 0;
  }
  run_scene(scene, options, comm);
  return 0;
}

} // namespace narrows::continuum
