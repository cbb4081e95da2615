// Engine "continuum": describe, run (over the run shell), check/info (see continuum/driver.hpp).
#include "narrows/continuum/driver.hpp"

#include "narrows/continuum/exact.hpp"
#include "narrows/continuum/flux.hpp"
#include "narrows/continuum/jamming_driver.hpp"
#include "narrows/continuum/plan.hpp"
#include "narrows/continuum/scheme.hpp"
#include "narrows/continuum/shock.hpp"
#include "narrows/core/error.hpp"
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

std::string fmt(const char *format, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[400];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

// The plan, with a refusal naming the scene file.
Plan plan_of(const scene::Scene &scene) {
  try {
    return make_plan(*scene.continuum);
  } catch (const Error &e) {
    throw input_error(scene.file + ": " + e.what());
  }
}

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

bool wants(const scene::Scene &scene, const char *name) {
  const auto &o = scene.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

} // namespace

std::vector<std::string> describe(const scene::Scene &scene) {
  if (scene.continuum->model == scene::ContinuumModel::jamming)
    return describe_jamming(scene);
  const scene::Continuum &m = *scene.continuum;
  const Flux flux(m);
  const Plan p = plan_of(scene);
  std::vector<std::string> out;
  out.push_back("engine continuum: conservation law rho_t + J(rho)_x = D rho_xx in 1D, D = " +
                fmt("%g", m.diffusion));
  out.push_back("flux: " + flux.describe());
  out.push_back("grid: " + std::to_string(m.cells) + " cells of dx = " + fmt("%g", p.grid.dx) +
                " on [0, " + fmt("%g", m.length) + "], " +
                (p.grid.periodic ? std::string("periodic")
                                 : "open: reservoirs held at " +
                                       fmt("%g left, %g right", p.grid.left, p.grid.right)));
  switch (m.initial) {
  case scene::ContinuumInitial::riemann:
    out.push_back("initial: Riemann problem " +
                  fmt("%g | %g at x = %g", m.left, m.right, m.position));
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
    out.push_back("initial: " + fmt("%g + %g sin(2 pi x / %g)", m.mean, m.amplitude, m.length));
    break;
  }
  Riemann rp;
  if (riemann_of(m, flux, rp)) {
    if (rp.shock)
      out.push_back("exact: a shock at the Rankine-Hugoniot speed " + fmt("%.6g", rp.speed));
    else if (m.left != m.right)
      out.push_back("exact: a rarefaction fan, x/t from " +
                    fmt("%.6g to %.6g", rp.fan_lo, rp.fan_hi));
  }
  out.push_back(std::string("scheme: finite volumes, MUSCL with the ") +
                (m.limiter == scene::ContinuumLimiter::mc ? "monotonised central" : "minmod") +
                " limiter, Rusanov (local Lax-Friedrichs) flux, central diffusion, SSP-RK2 "
                "(second order where smooth)");
  out.push_back(
      "time step: dt = " +
      fmt("%.6g (CFL %g: max|J'| = %.6g over [%g, ", p.dt, m.cfl, p.max_speed, p.lo) +
      fmt("%g]; Courant number %.4g, D dt/dx^2 = %.4g)", p.hi, p.courant, p.diffusion_number));
  out.push_back("time: " + fmt("%g", m.time) + " in " + std::to_string(p.steps) + " steps; " +
                std::to_string(m.samples) + " samples (every " + std::to_string(p.per_sample) +
                " steps) and t = 0");
  out.push_back("ranks: every rank advances the same cells (no decomposition); memory about " +
                fmt("%.3g MiB", 7.0 * 8.0 * static_cast<double>(m.cells) / 1048576.0));
  return out;
}

void run_scene(const scene::Scene &scene, const run::Options &options, MPI_Comm comm) {
  if (scene.continuum->model == scene::ContinuumModel::jamming) {
    run_jamming(scene, options, comm);
    return;
  }
  const scene::Continuum &m = *scene.continuum;
  const Plan p = plan_of(scene);
  const Flux flux(m);
  const std::size_t n = static_cast<std::size_t>(m.cells);

  run::Shell shell(scene, options, comm, {p.steps, "continuum.time", {}});
  const int rank = shell.rank();
  std::vector<double> u = initial_cells(m);
  std::int64_t step = 0;
  const bool restarting = shell.restarting();
  if (restarting)
    run::collectively(comm, [&] {
      const std::string &file = shell.restart_file();
      const auto dt = io::read_checkpoint_array(file, "continuum/time_step", 1, comm);
      if (dt[0] != p.dt)
        throw input_error(file + ": /continuum/time_step = " + fmt("%.17g", dt[0]) +
                          " but this scene's time step is " + fmt("%.17g", p.dt) +
                          "; allowed: the checkpoint of this scene");
      u = io::read_checkpoint_array(file, "continuum/density", n, comm);
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(u[i]))
          throw input_error(file + ": /continuum/density[" + std::to_string(i) +
                            "] is not finite; allowed: finite densities");
      step = shell.restart_info().step;
    });

  run::Log &log = shell.open(restarting ? step : -1);
  for (const auto &line : describe(scene))
    log.line(line);
  if (restarting)
    log.line("restarted from " + shell.restart_file() + " at step " + std::to_string(step) +
             fmt(" (t = %.6g)", static_cast<double>(step) * p.dt));

  std::unique_ptr<io::ObservablesWriter> writer;
  if (rank == 0)
    writer = std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene.text);
  const std::vector<double> bins = cell_centres(p.grid);
  std::vector<double> shock_t, shock_x;
  const auto sample = [&](std::int64_t s) {
    const double t = static_cast<double>(s) * p.dt;
    const double x = shock_position(u, p.grid.dx, p.grid.periodic);
    shock_t.push_back(t);
    shock_x.push_back(x);
    if (rank != 0)
      return;
    if (wants(scene, "density"))
      writer->append_profile("density", s, t, bins, u, 1);
    if (wants(scene, "shock_position"))
      writer->append_scalar("shock_position", s, t, x);
    writer->flush();
  };
  const auto save = [&](std::int64_t s) {
    return shell.checkpoint(s, [&](const std::string &path) {
      io::CheckpointInfo info = shell.checkpoint_info(s, static_cast<double>(s) * p.dt);
      info.dimensions = 1;
      info.box = {m.length, 1.0, 1.0};
      io::write_checkpoint(path, info, {}, comm,
                           {{"continuum/time_step", {p.dt}}, {"continuum/density", u}});
      return "step " + std::to_string(s) + fmt(", t = %.6g", static_cast<double>(s) * p.dt);
    });
  };

  Scheme scheme(flux, p.grid, m.diffusion, m.limiter);
  if (!restarting)
    sample(0);
  const std::int64_t first = step;
  shell.start_loop(first);
  while (step < p.steps) {
    scheme.step(u, p.dt);
    ++step;
    if (step % p.per_sample == 0) {
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(u[i]))
          throw invariant_error(scene.file + ": density of cell " + std::to_string(i) +
                                " is not finite at step " + std::to_string(step) +
                                "; the scheme is unstable (report it)");
      sample(step);
    }
    if (shell.checkpoint_due(step))
      save(step);
    if ((step % 64 == 0 || step % p.per_sample == 0) && step < p.steps && shell.stop_requested())
      break;
    shell.progress(step, static_cast<double>(n), "cell-steps/s");
  }
  const double seconds = shell.loop_seconds();
  const std::string last = save(step);
  if (shell.stopped()) {
    shell.finish("step " + std::to_string(step), last);
    return;
  }
  Riemann rp;
  if (shock_t.size() >= 3 && riemann_of(m, flux, rp) && rp.shock) {
    // Speed over the second half of this run's samples (the profile has settled by then).
    const std::size_t a = shock_t.size() / 2, b = shock_t.size() - 1;
    const double v = (shock_x[b] - shock_x[a]) / (shock_t[b] - shock_t[a]);
    log.line(fmt("shock: at x = %.6g at t = %.6g, speed %.6g (Rankine-Hugoniot %.6g)", shock_x[b],
                 shock_t[b], v, rp.speed));
  }
  const double mass = [&] {
    double s = 0.0;
    for (double x : u)
      s += x;
    return s * p.grid.dx;
  }();
  log.line(fmt("total density (mass) at t = %.6g: %.12g", static_cast<double>(step) * p.dt, mass));
  const auto steps_done = static_cast<std::uint64_t>(step - first);
  shell.loop_time(seconds, steps_done, "steps", std::to_string(n) + " cells",
                  static_cast<double>(steps_done) * static_cast<double>(n), "cell-steps");
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
