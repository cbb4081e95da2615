// Engine "continuum": describe, check/info, the engine of the run loop (see continuum/driver.hpp).
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
  case scene::ContinuumInitial::eigenmode:
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

namespace {

// The conservation law rho_t + J(rho)_x = D rho_xx on its finite-volume scheme.
class ConservationLaw final : public FieldModel {
public:
  explicit ConservationLaw(const scene::Scene &scene)
      : scene_(scene), m_(*scene.continuum), p_(plan_of(scene, make_plan)), flux_(m_),
        u_(initial_cells(m_)), scheme_(flux_, p_.grid, m_.diffusion, m_.limiter),
        bins_(cell_centres(p_.grid)) {
    dt = p_.dt;
    steps = p_.steps;
    per_sample = p_.per_sample;
    points = u_.size();
    lines = describe(scene);
    fields = {{"density", &u_}};
  }

  void step(double dt) override { scheme_.step(u_, dt); }
  void check(std::int64_t step) const override {
    for (std::size_t i = 0; i < u_.size(); ++i)
      if (!std::isfinite(u_[i]))
        throw invariant_error(scene_.file + ": density of cell " + std::to_string(i) +
                              " is not finite at step " + std::to_string(step) +
                              "; the scheme is unstable (report it)");
  }
  std::string restored_out_of_range() const override {
    // The scheme keeps the solution within the range of its initial and boundary data (the
    // maximum principle of scalar conservation laws, kept by the limited MUSCL scheme), up to
    // rounding.
    const double tol = 1e-9 * (p_.hi - p_.lo) + 1e-12 * (1.0 + std::abs(p_.lo) + std::abs(p_.hi));
    for (std::size_t i = 0; i < u_.size(); ++i)
      if (!(u_[i] >= p_.lo - tol && u_[i] <= p_.hi + tol))
        return "density[" + std::to_string(i) + "] = " + format("%.17g", u_[i]) +
               "; allowed: " + format("%.17g to %.17g", p_.lo, p_.hi) +
               ", the range of the scene's initial and boundary densities, which the "
               "conservation law keeps";
    return {};
  }
  void sample(io::ObservablesWriter *writer, std::int64_t s, double t) override {
    const double x = shock_position(u_, p_.grid.dx, p_.grid.periodic);
    shock_t_.push_back(t);
    shock_x_.push_back(x);
    if (writer == nullptr)
      return;
    if (wants(scene_, "density"))
      writer->append_profile("density", s, t, bins_, u_, 1);
    if (wants(scene_, "shock_position"))
      writer->append_scalar("shock_position", s, t, x);
  }
  void summary(run::Log &log, std::int64_t step) const override {
    Riemann rp;
    if (shock_t_.size() >= 3 && riemann_of(m_, flux_, rp) && rp.shock) {
      // Speed over the second half of this run's samples (the profile has settled by then).
      const std::size_t a = shock_t_.size() / 2, b = shock_t_.size() - 1;
      const double v = (shock_x_[b] - shock_x_[a]) / (shock_t_[b] - shock_t_[a]);
      log.line(format("shock: at x = %.6g at t = %.6g, speed %.6g (Rankine-Hugoniot %.6g)",
                      shock_x_[b], shock_t_[b], v, rp.speed));
    }
    double mass = 0.0;
    for (const double x : u_)
      mass += x;
    log.line(format("total density (mass) at t = %.6g: %.12g", static_cast<double>(step) * p_.dt,
                    mass * p_.grid.dx));
  }

private:
  const scene::Scene &scene_;
  const scene::Continuum &m_;
  const Plan p_;
  const Flux flux_;
  std::vector<double> u_;
  Scheme scheme_;
  const std::vector<double> bins_;
  std::vector<double> shock_t_, shock_x_;
};

} // namespace

std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm) {
  check_memory(scene, comm);
  return describe(scene);
}

std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &,
                                         MPI_Comm comm) {
  check_memory(scene, comm);
  switch (scene.continuum->model) {
  case scene::ContinuumModel::jamming:
    return field_engine(scene, comm, make_jamming(scene));
  case scene::ContinuumModel::segregation:
    return field_engine(scene, comm, make_segregation(scene));
  default:
    return field_engine(scene, comm, std::make_unique<ConservationLaw>(scene));
  }
}

} // namespace narrows::continuum
