// Engine "continuum", model "jamming" (see continuum/jamming_driver.hpp).
#include "narrows/continuum/jamming_driver.hpp"

#include "narrows/continuum/jamming_model.hpp"
#include "narrows/continuum/jamming_plan.hpp"
#include "narrows/continuum/jamming_solver.hpp"
#include "narrows/continuum/jamming_stability.hpp"
#include "narrows/core/error.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/run/collective.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

namespace narrows::continuum {

namespace {

std::string fmt(const char *format, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[400];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

JammingPlan plan_of(const scene::Scene &scene) {
  try {
    return make_jamming_plan(*scene.continuum);
  } catch (const Error &e) {
    throw input_error(scene.file + ": " + e.what());
  }
}

bool wants(const scene::Scene &scene, const char *name) {
  const auto &o = scene.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

double mean_of(const std::vector<double> &x) {
  double s = 0.0;
  for (double y : x)
    s += y;
  return s / static_cast<double>(x.size());
}

} // namespace

std::vector<std::string> describe_jamming(const scene::Scene &scene) {
  const scene::Continuum &m = *scene.continuum;
  const JammingModel model(m);
  const JammingPlan p = plan_of(scene);
  std::vector<std::string> out;
  out.push_back("engine continuum: jamming model phi_t + (phi v)_x = D phi_xx, v_t + v v_x = "
                "sigma - xi(phi) v (seed 001 eq 6.2-6.6), D = " +
                fmt("%g, sigma = %g", m.diffusion, m.drive));
  out.push_back("friction: " + model.describe());
  out.push_back("grid: " + std::to_string(m.cells) + " points x_i = i dx, dx = " + fmt("%g", p.dx) +
                " on [0, " + fmt("%g", m.length) + "), periodic");
  switch (m.initial) {
  case scene::ContinuumInitial::sine:
    out.push_back("initial: phi = " +
                  fmt("%g + %g sin(2 pi %g x / %g)", m.mean, m.amplitude,
                      static_cast<double>(m.mode), m.length) +
                  ", v = v_ss(phi)");
    break;
  case scene::ContinuumInitial::random:
    out.push_back(
        "initial: phi = " + fmt("%g + %g u_i, u_i uniform in (-1, 1), seed ", m.mean, m.amplitude) +
        std::to_string(m.seed) + ", v = v_ss(phi)");
    break;
  default:
    out.push_back(std::string("initial: the given phi") +
                  (m.velocity.empty() ? ", v = v_ss(phi)" : " and v"));
    break;
  }
  std::vector<double> phi, v;
  jamming_initial(m, phi, v);
  const double phi0 = mean_of(phi);
  const double dk = 2.0 * std::numbers::pi / m.length;
  const double k_edge = unstable_band_edge(model, phi0, 200.0 * dk + 20.0);
  if (k_edge > 0.0) {
    double best = 0.0, best_k = 0.0;
    for (int i = 1; i <= 1000; ++i) {
      const double k = k_edge * i / 1000.0;
      const double g = growth_rate(model, phi0, k).real();
      if (g > best) {
        best = g;
        best_k = k;
      }
    }
    out.push_back("stability (eq 6.11) of phi = " +
                  fmt("%g, v = %g: unstable band 0 < k < %.6g", phi0, model.vss(phi0), k_edge) +
                  fmt(" (modes n < %.4g of 2 pi n / length); fastest k = %.4g grows at %.4g",
                      k_edge / dk, best_k, best));
  } else {
    out.push_back("stability (eq 6.11) of phi = " +
                  fmt("%g, v = %g: homogeneous flow is linearly stable", phi0, model.vss(phi0)));
  }
  if (phi0 >= model.fit().phi_q)
    out.push_back("warning: the mean phi = " +
                  fmt("%g is at or beyond phi_q = %g, where the fit's v_ss (eq 6.4) reaches 0 and "
                      "rises again: outside the range of the seed's data (fig 6.8)",
                      phi0, model.fit().phi_q));
  out.push_back("stability boundary in the (phi, drive) plane: flow at phi = " +
                fmt("%g is unstable to long waves for drive < %.6g (phi^2 v_ss'^2 v_ss / D)", phi0,
                    critical_drive(model, phi0)));
  out.push_back("scheme: pseudo-spectral (FFTW), 2/3 rule (modes |n| < " +
                std::to_string((m.cells + 2) / 3) +
                "), Strang splitting: exact friction relaxation, IF-RK4 transport with exact "
                "diffusion (second order in time)");
  out.push_back("time step: dt = " + fmt("%.6g (CFL %g: speed bound %.6g; Courant number %.4g)",
                                         p.dt, m.cfl, p.speed_bound, p.courant));
  out.push_back("time: " + fmt("%g", m.time) + " in " + std::to_string(p.steps) + " steps; " +
                std::to_string(m.samples) + " samples (every " + std::to_string(p.per_sample) +
                " steps) and t = 0");
  out.push_back("ranks: every rank advances the same points (no decomposition); memory about " +
                fmt("%.3g MiB", 40.0 * 8.0 * static_cast<double>(m.cells) / 1048576.0));
  return out;
}

void run_jamming(const scene::Scene &scene, const run::Options &options, MPI_Comm comm) {
  const scene::Continuum &m = *scene.continuum;
  const JammingPlan p = plan_of(scene);
  const JammingModel model(m);
  const std::size_t n = static_cast<std::size_t>(m.cells);

  run::Shell shell(scene, options, comm, {p.steps, "continuum.time", {}});
  const int rank = shell.rank();
  std::vector<double> phi, v;
  jamming_initial(m, phi, v);
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
      phi = io::read_checkpoint_array(file, "continuum/density", n, comm);
      v = io::read_checkpoint_array(file, "continuum/velocity", n, comm);
      for (const auto &[name, x] : {std::pair{"density", &phi}, std::pair{"velocity", &v}})
        for (std::size_t i = 0; i < n; ++i)
          if (!std::isfinite((*x)[i]))
            throw input_error(file + ": /continuum/" + name + "[" + std::to_string(i) +
                              "] is not finite; allowed: finite values");
      step = shell.restart_info().step;
    });

  run::Log &log = shell.open(restarting ? step : -1);
  for (const auto &line : describe_jamming(scene))
    log.line(line);
  if (restarting)
    log.line("restarted from " + shell.restart_file() + " at step " + std::to_string(step) +
             fmt(" (t = %.6g)", static_cast<double>(step) * p.dt));

  std::unique_ptr<io::ObservablesWriter> writer;
  if (rank == 0)
    writer = std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene.text);
  const std::vector<double> bins = jamming_points(p);
  const auto sample = [&](std::int64_t s) {
    if (rank != 0)
      return;
    const double t = static_cast<double>(s) * p.dt;
    if (wants(scene, "density"))
      writer->append_profile("density", s, t, bins, phi, 1);
    if (wants(scene, "velocity"))
      writer->append_profile("velocity", s, t, bins, v, 1);
    writer->flush();
  };
  const auto save = [&](std::int64_t s) {
    return shell.checkpoint(s, [&](const std::string &path) {
      io::CheckpointInfo info = shell.checkpoint_info(s, static_cast<double>(s) * p.dt);
      info.dimensions = 1;
      info.box = {m.length, 1.0, 1.0};
      io::write_checkpoint(
          path, info, {}, comm,
          {{"continuum/time_step", {p.dt}}, {"continuum/density", phi}, {"continuum/velocity", v}});
      return "step " + std::to_string(s) + fmt(", t = %.6g", static_cast<double>(s) * p.dt);
    });
  };

  JammingSolver solver(model, n, m.length);
  if (!restarting)
    sample(0);
  const std::int64_t first = step;
  shell.start_loop(first);
  while (step < p.steps) {
    solver.step(phi, v, p.dt);
    ++step;
    if (step % p.per_sample == 0) {
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(phi[i]) || !std::isfinite(v[i]) || std::abs(v[i]) * p.dt > p.dx)
          throw invariant_error(scene.file + ": phi or v at point " + std::to_string(i) +
                                " is not finite or beyond the Courant limit at step " +
                                std::to_string(step) + fmt(" (phi = %g, v = %g)", phi[i], v[i]) +
                                "; allowed: a smaller continuum.cfl or more continuum.cells");
      sample(step);
    }
    if (shell.checkpoint_due(step))
      save(step);
    if ((step % 64 == 0 || step % p.per_sample == 0) && step < p.steps && shell.stop_requested())
      break;
    shell.progress(step, static_cast<double>(n), "point-steps/s");
  }
  const double seconds = shell.loop_seconds();
  const std::string last = save(step);
  if (shell.stopped()) {
    shell.finish("step " + std::to_string(step), last);
    return;
  }
  const auto [lo, hi] = std::minmax_element(phi.begin(), phi.end());
  log.line(fmt("phi at t = %.6g: mean %.12g (mass / length), min %.6g, max %.6g",
               static_cast<double>(step) * p.dt, mean_of(phi), *lo, *hi));
  const auto steps_done = static_cast<std::uint64_t>(step - first);
  shell.loop_time(seconds, steps_done, "steps", std::to_string(n) + " points",
                  static_cast<double>(steps_done) * static_cast<double>(n), "point-steps");
}

} // namespace narrows::continuum
