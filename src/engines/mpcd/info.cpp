// `narrows info` / `check`: describe the pipeline and the physical regime of a scene.
#include "narrows/engines/mpcd/info.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/engines/mpcd/transport_theory.hpp"
#include "narrows/run/collective.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace narrows::mpcd {

namespace {

std::string fmt(const char *format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

struct Regime {
  std::optional<mpcd::Viscosity> nu;
  double sound_speed = 0.0;
  double u0 = 0.0; // flow scale (sine force), 0 if none
  double mach = 0.0, reynolds = 0.0;
  double kolmogorov_re = 0.0; // u0/(k nu): the laminar flow is unstable above sqrt(2)
  bool poiseuille = false;    // walls and a force along x: u0 = g L_y^2 / (8 nu)
};

Regime regime(const scene::Scene &s) {
  Regime r;
  const int d = s.run.dimensions;
  const double angle = s.fluid.angle_deg * std::numbers::pi / 180.0;
  r.nu = mpcd::viscosity(s.fluid.collision, d, s.fluid.density, s.fluid.dt, angle, s.fluid.kT);
  // Ideal gas: c_s = sqrt(gamma kT/m), gamma = (d + 2)/d.
  r.sound_speed = std::sqrt((d + 2.0) / d * s.fluid.kT);
  if (s.body_force && s.body_force->kind == scene::ForceKind::sine && r.nu) {
    const double L = s.domain.size[1];
    r.u0 = std::abs(s.body_force->amplitude) * L * L /
           (4.0 * std::numbers::pi * std::numbers::pi * r.nu->total());
    r.mach = r.u0 / r.sound_speed;
    r.reynolds = r.u0 * L / r.nu->total();
    r.kolmogorov_re = r.u0 * L / (2.0 * std::numbers::pi * r.nu->total());
  }
  if (s.walls && s.body_force && r.nu) {
    const double L = s.domain.size[1];
    r.poiseuille = true;
    r.u0 = std::abs(s.body_force->value[0]) * L * L / (8.0 * r.nu->total());
    r.mach = r.u0 / r.sound_speed;
    r.reynolds = r.u0 * L / r.nu->total();
  }
  return r;
}

using run::memory_per_rank; // the machine's memory per rank of comm on this node

// Mean free path lambda = dt sqrt(kT/m) beyond which positions are noise: a particle flies a
// million cells a step, and its wrapped position keeps fewer than 10 significant digits.
constexpr double max_free_path = 1e6;

// The memory a rank of comm needs (the estimate shared evenly over the ranks).
double memory_of_rank(const scene::Scene &s, MPI_Comm comm) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  return static_cast<double>(estimate_memory(s)) / ranks;
}

} // namespace

void check_runnable(const scene::Scene &s, MPI_Comm comm) {
  const std::string head = s.file + ": ";
  const double lambda = s.fluid.dt * std::sqrt(s.fluid.kT);
  if (!(lambda <= max_free_path))
    throw input_error(head + "mean free path dt sqrt(kT/m) = " + fmt("%.3g", lambda) +
                      " cells (fluid.dt = " + fmt("%.3g", s.fluid.dt) +
                      ", fluid.kT = " + fmt("%.3g", s.fluid.kT) + "); allowed: at most " +
                      fmt("%g", max_free_path) + " (beyond it positions are noise)");
  // The invariant check stops a run at a particle speed above max_speed; a Maxwell velocity
  // component exceeds 10 sqrt(kT/m) with probability 1.5e-23 per draw, so below this bound no
  // run stops for its temperature alone.
  const double hottest = (max_speed / 10.0) * (max_speed / 10.0);
  if (!(s.fluid.kT <= hottest))
    throw input_error(head + "fluid.kT = " + fmt("%.3g", s.fluid.kT) +
                      " gives thermal speeds the run refuses (it stops at speed " +
                      fmt("%g", max_speed) + "); allowed: at most " + fmt("%g", hottest));
  if (s.body_force) {
    // The flight per step the force alone gives by the end of the run (the fluid accelerates
    // until the walls or collisions hold it): beyond the bound positions are noise, and the
    // periodic wrap (fmod of huge numbers) takes far longer than a step should.
    double g = std::abs(s.body_force->amplitude);
    for (int k = 0; k < s.run.dimensions; ++k)
      g = std::max(g, std::abs(s.body_force->value[k]));
    const double flight =
        g * s.fluid.dt * s.fluid.dt * std::max<double>(1.0, static_cast<double>(s.run.steps));
    if (!(flight <= max_free_path))
      throw input_error(head + "the body force " + fmt("%.3g", g) + " moves a particle " +
                        fmt("%.3g", flight) + " cells per step by step " +
                        std::to_string(s.run.steps) + " (fluid.dt = " + fmt("%.3g", s.fluid.dt) +
                        "); allowed: at most " + fmt("%g", max_free_path));
  }
  // Cells and particles as counted before anything is allocated (doubles: no overflow).
  double cells = 1.0;
  for (int k = 0; k < s.run.dimensions; ++k)
    cells *= std::round(s.domain.size[k]);
  const double expected = cells * s.fluid.density;
  if (expected > 1e15)
    throw input_error(head + "fluid.density = " + fmt("%g", s.fluid.density) + " in " +
                      fmt("%.3g", cells) + " cells gives " + fmt("%.3g", expected) +
                      " fluid particles; allowed: at most 1e15");
  if (particle_count(s) == 0)
    throw input_error(head + "fluid.density = " + fmt("%g", s.fluid.density) + " in " +
                      fmt("%.3g", cells) +
                      " cells gives 0 fluid particles; allowed: a density giving at least one");
  const double need = memory_of_rank(s, comm), have = memory_per_rank(comm);
  if (need > have)
    throw input_error(head + "needs about " + fmt("%.3g", need / 1048576.0) +
                      " MiB per rank, this machine has " + fmt("%.3g", have / 1048576.0) +
                      " MiB per rank; allowed: a scene that fits (more ranks or nodes, a smaller "
                      "box or density)");
  if (s.colloids) {
    // MD with a thermal colloid velocity that crosses its own radius in one sub-step cannot
    // resolve a collision: the integrator is unstable.
    // With several kinds, each kind's radius and mass.
    const auto &spec = *s.colloids;
    std::vector<scene::ColloidKind> kinds = spec.kinds;
    if (kinds.empty())
      kinds.push_back({spec.radius, spec.mass, spec.count});
    std::uint64_t first = 0;
    for (const auto &kind : kinds) {
      const double r = kind.radius;
      const double m = spec.mass_of_id(s.run.dimensions, s.fluid.density, first, r);
      first += static_cast<std::uint64_t>(kind.count);
      const double step = std::sqrt(s.fluid.kT / m) * s.fluid.dt / spec.md_substeps;
      if (!(step <= r))
        throw input_error(
            head + "a colloid's thermal velocity sqrt(kT/M) moves it " + fmt("%.3g", step) +
            " per MD sub-step (mass " + fmt("%.3g", m) + ", fluid.dt / colloids.md_substeps = " +
            fmt("%.3g", s.fluid.dt / spec.md_substeps) + "); allowed: at most its radius " +
            fmt("%g", r) + " (raise colloids.mass or md_substeps, lower fluid.dt)");
    }
  }
}

std::vector<std::string> describe_scene(const scene::Scene &s, MPI_Comm comm) {
  check_runnable(s, comm);
  const MpcdSimulation plan(s, comm, false);
  return describe_simulation(plan);
}

std::vector<std::string> describe_simulation(const MpcdSimulation &sim) {
  const scene::Scene &s = sim.scene();
  const MPI_Comm comm = sim.comm();
  std::vector<std::string> out;
  const int d = s.run.dimensions;
  std::string box = "box ";
  for (int k = 0; k < d; ++k)
    box += fmt("%g", s.domain.size[k]) + (k + 1 < d ? " x " : " cells, ");
  if (s.walls)
    box += std::string(s.walls->slip ? "slip" : "no-slip") +
           " walls at y = 0 and y = " + fmt("%g", s.domain.size[1]) +
           (d == 3 ? ", periodic in x and z" : ", periodic in x") +
           (s.walls->virtual_particles ? ", virtual particles in cut cells"
                                       : ", no virtual particles");
  else
    box += "periodic";
  out.push_back(std::string("engine mpcd, ") + std::to_string(d) + "D, " + box + ", seed " +
                std::to_string(s.run.seed) + ", " + std::to_string(s.run.steps) + " steps");
  out.push_back("pipeline (per step):");
  for (auto &line : describe_pipeline(sim.stages()))
    out.push_back(std::move(line));
  std::string obs;
  for (const auto &o : s.output.observables)
    obs += (obs.empty() ? "" : ", ") + o;
  out.push_back("  then every " + std::to_string(s.output.every) + " steps: observables [" + obs +
                "] and invariant checks");
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  out.push_back("particles: " + std::to_string(particle_count(s)) + " fluid (density " +
                fmt("%g", s.fluid.density) + " per cell)");
  out.push_back("memory: " + fmt("%.1f", estimate_memory(s) / 1048576.0) + " MiB (estimate" +
                (ranks > 1 ? ", " + fmt("%.1f", estimate_memory(s) / 1048576.0 / ranks) +
                                 " MiB per rank on " + std::to_string(ranks) + " ranks)"
                           : ")"));
  out.push_back("mean free path lambda = dt sqrt(kT/m) = " +
                fmt("%.4g", s.fluid.dt * std::sqrt(s.fluid.kT)) + " a");
  const Regime r = regime(s);
  if (r.nu) {
    std::string line = "viscosity (kinetic theory): nu = " + fmt("%.5g", r.nu->total()) +
                       " (kinetic " + fmt("%.5g", r.nu->kinetic) + ", collisional " +
                       fmt("%.5g", r.nu->collisional) + ")";
    if (s.fluid.collision == scene::Collision::srd) {
      const double D = mpcd::srd_self_diffusion(
          d, s.fluid.density, s.fluid.dt, s.fluid.angle_deg * std::numbers::pi / 180.0, s.fluid.kT);
      line += ", self-diffusion D = " + fmt("%.5g", D) +
              ", Sc = nu/D = " + fmt("%.3g", r.nu->total() / D);
    }
    out.push_back(line);
  } else {
    out.push_back("viscosity: no kinetic-theory formula for this rule in " + std::to_string(d) +
                  "D");
  }
  if (s.body_force) {
    if (s.body_force->kind == scene::ForceKind::sine && r.nu) {
      out.push_back("Kolmogorov flow: u0 = F0 L^2/(4 pi^2 nu) = " + fmt("%.4g", r.u0) +
                    ", Ma = u0/c_s = " + fmt("%.3g", r.mach) + " (c_s = " +
                    fmt("%.4g", r.sound_speed) + "), Re = u0 L_y/nu = " + fmt("%.3g", r.reynolds) +
                    ", Re_k = u0/(k nu) = " + fmt("%.3g", r.kolmogorov_re));
    } else if (r.poiseuille) {
      out.push_back("Poiseuille channel: u0 = g_x L_y^2/(8 nu) = " + fmt("%.4g", r.u0) +
                    ", Ma = u0/c_s = " + fmt("%.3g", r.mach) + " (c_s = " +
                    fmt("%.4g", r.sound_speed) + "), Re = u0 L_y/nu = " + fmt("%.3g", r.reynolds));
    } else if (s.body_force->kind == scene::ForceKind::constant && !s.walls) {
      double g = 0.0;
      for (int k = 0; k < d; ++k)
        g += s.body_force->value[k] * s.body_force->value[k];
      g = std::sqrt(g);
      const double t_end = s.run.steps * s.fluid.dt;
      out.push_back("constant force |g| = " + fmt("%.4g", g) +
                    " in a periodic box: the fluid accelerates uniformly, Ma at the end = " +
                    fmt("%.3g", g * t_end / r.sound_speed));
    }
  }
  return out;
}

void check_colloid_placement(const scene::Scene &s) {
  if (!s.colloids)
    return;
  try {
    place_colloids(*s.colloids, make_box(s), s.fluid.density, s.run.seed);
  } catch (const Error &e) {
    if (e.code() != ExitCode::bad_input)
      throw;
    throw input_error(s.file + ": " + e.what());
  }
}

std::vector<std::string> regime_warnings(const scene::Scene &s) {
  std::vector<std::string> w;
  const Regime r = regime(s);
  const double need = memory_of_rank(s, MPI_COMM_WORLD), have = memory_per_rank(MPI_COMM_WORLD);
  if (need > 0.5 * have)
    w.push_back("needs about " + fmt("%.3g", need / 1048576.0) +
                " MiB per rank, more than half "
                "of this machine's " +
                fmt("%.3g", have / 1048576.0) + " MiB per rank");
  const double lambda = s.fluid.dt * std::sqrt(s.fluid.kT);
  double smallest = s.domain.size[0];
  for (int k = 1; k < s.run.dimensions; ++k)
    smallest = std::min(smallest, s.domain.size[k]);
  if (lambda > smallest)
    w.push_back("mean free path " + fmt("%.3g", lambda) + " exceeds the box edge " +
                fmt("%g", smallest) + ": particles cross the box in one step");
  if (r.mach > 0.2)
    w.push_back("Ma = " + fmt("%.3g", r.mach) +
                " > 0.2: compressibility effects are not negligible (Kanehl (thesis) §4.3)");
  if (r.kolmogorov_re > 1.0 && s.domain.size[0] > s.domain.size[1])
    w.push_back("Re_k = u0/(k nu) = " + fmt("%.3g", r.kolmogorov_re) +
                " > 1 in a box longer than wide: the laminar Kolmogorov flow becomes unstable "
                "near sqrt(2) and the profile no longer measures nu");
  if (r.poiseuille && r.reynolds > 0.2)
    w.push_back("Re = " + fmt("%.3g", r.reynolds) +
                " > 0.2: inertia is not negligible for colloid flows (Kanehl (thesis) §4.3)");
  if (s.body_force && s.body_force->kind == scene::ForceKind::constant && !s.walls) {
    double g2 = 0.0;
    for (int k = 0; k < s.run.dimensions; ++k)
      g2 += s.body_force->value[k] * s.body_force->value[k];
    const double ma_end = std::sqrt(g2) * s.run.steps * s.fluid.dt / r.sound_speed;
    if (ma_end > 0.2)
      w.push_back("constant force without walls: the mean flow reaches Ma = " +
                  fmt("%.3g", ma_end) + " by the end of the run");
  }
  if (s.colloids && s.body_force &&
      s.body_force->acts_on == scene::DriveTarget::fluid_and_colloids &&
      s.colloids->gravity != std::array<double, 3>{0.0, 0.0, 0.0} &&
      s.colloids->gravity == s.body_force->value)
    w.push_back("colloids.gravity equals body_force.value and body_force.acts_on = "
                "\"fluid+colloids\": the colloids feel the drive twice (M g from each); the "
                "drive alone is body_force.acts_on");
  if (s.fluid.dt * std::sqrt(s.fluid.kT) < 0.5 && r.nu)
    w.push_back("mean free path " + fmt("%.3g", s.fluid.dt * std::sqrt(s.fluid.kT)) +
                " < 0.5 a: kinetic-theory transport coefficients may be off by up to ~15 %");
  return w;
}

} // namespace narrows::mpcd
