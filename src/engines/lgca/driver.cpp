// Engine "lgca": scene -> lattice, check/info text, the engines of the run loop (FHP lattices
// with observables, checkpoints and restarts; the d'Humieres model's replicas), and the lattice
// benchmark.
#include "narrows/engines/lgca/driver.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/lgca/colloid_correlations.hpp"
#include "narrows/engines/lgca/dhumieres_vacf.hpp"
#include "narrows/engines/lgca/fhp_checkpoint.hpp"
#include "narrows/engines/lgca/fhp_colloid.hpp"
#include "narrows/engines/lgca/fhp_observables.hpp"
#include "narrows/engines/lgca/fhp_tagged.hpp"
#include "narrows/engines/lgca/fhp_update.hpp"
#include "narrows/engines/lgca/vacf_theory.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/run/engine.hpp"
#include "narrows/run/shell.hpp"
#include "narrows/scene/parse.hpp"

#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace narrows::lgca {

namespace {

constexpr double sqrt3_2 = 0.8660254037844386;
constexpr double two_pi = 6.283185307179586;

std::string fmt(const char *format, double v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

bool wants(const scene::Scene &s, const char *name) {
  const auto &o = s.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

// Scenes the engine cannot run: one line, exit code 2.
void refuse_unavailable(const scene::Scene &scene) {
  if (scene.lgca->model == scene::LgcaModel::dhumieres_1d && !scene.tagged)
    throw input_error(scene.file +
                      ": lattice.model = \"dhumieres-1d\" measures the tagged VACF and needs a "
                      "[tagged] section; allowed: [tagged] max_lag = ..., replicas = ...");
  if (!scene.tagged && wants(scene, "vacf"))
    throw input_error(scene.file +
                      ": output.observables lists \"vacf\" without a [tagged] section; allowed: "
                      "add [tagged] max_lag = ... or drop \"vacf\"");
}

// Everything written every output.every steps (rank 0 writes).
class Observer {
public:
  Observer(const scene::Scene &scene, const FhpLattice &lattice,
           std::unique_ptr<io::ObservablesWriter> writer)
      : writer_(std::move(writer)), fields_(lattice, static_cast<int>(scene.lgca->block)) {
    shear_ = wants(scene, "shear_wave");
    density_ = wants(scene, "density");
    velocity_ = wants(scene, "velocity");
  }
  void every_step(const FhpLattice &l) {
    if (density_ || velocity_)
      fields_.add(l);
  }
  void sample(const FhpLattice &l) {
    const std::int64_t step = l.time();
    const double t = static_cast<double>(step);
    if (shear_) {
      const double a = shear_wave_amplitude(l);
      if (writer_)
        writer_->append_scalar("shear_wave", step, t, a);
    }
    std::vector<double> rho, u;
    if ((density_ || velocity_) && fields_.finish(l.comm(), rho, u) && writer_) {
      const auto by = static_cast<hsize_t>(fields_.blocks_y()),
                 bx = static_cast<hsize_t>(fields_.blocks_x());
      if (density_)
        writer_->append_field("density", step, t, {by, bx}, rho);
      if (velocity_)
        writer_->append_field("velocity", step, t, {by, bx, 2}, u);
    }
    if (writer_)
      writer_->flush();
  }

private:
  std::unique_ptr<io::ObservablesWriter> writer_;
  FieldAccumulator fields_;
  bool shear_ = false, density_ = false, velocity_ = false;
};

// Kinetic theory beside the measured VACF (van der Hoef & Frenkel eq 19-22), for N expected
// particles.
struct TaggedTheory {
  double z1, d0, t0, correction, particles;
};
TaggedTheory tagged_theory(FhpModel m, double d, double sites) {
  const Links l = triangular_links(links(m) == 7);
  TaggedTheory th{};
  th.z1 = theory::one_step_vacf(l, d);
  th.d0 = theory::boltzmann_diffusion(theory::mean_square_velocity_x(l), th.z1);
  th.t0 = theory::mean_free_time(th.z1);
  th.particles = sites * links(m) * d;
  th.correction = theory::finite_size_correction(d, th.particles);
  return th;
}

// The VACF of the run: log lines and /observables/vacf (rank 0 writes).
void finish_vacf(const scene::Scene &scene, const FhpLattice &lattice, const FhpTagged &tagged,
                 run::Log &log, io::ObservablesWriter *writer) {
  if (tagged.curves() == 0) {
    log.line("tagged VACF: no curve of " + std::to_string(tagged.max_lag()) +
             " lags completed; nothing written");
    return;
  }
  const double d = scene.lgca->density;
  const double sites = static_cast<double>(lattice.size_x()) * lattice.size_y();
  TaggedTheory th = tagged_theory(lattice.params().model, d, sites);
  const std::vector<double> z = tagged.mean(), e = tagged.error();
  if (z.empty())
    return; // not rank 0
  th.particles = tagged.particles();
  th.correction = theory::finite_size_correction(d, th.particles);
  // N is conserved: eq 19 at the lattice's own density N / (b sites) is the one to compare
  // with (the initial draw misses d by ~ sqrt(d (1 - d) / (b sites))).
  const double d_lattice = th.particles / (links(lattice.params().model) * sites);
  const double z1_lattice =
      theory::one_step_vacf(triangular_links(links(lattice.params().model) == 7), d_lattice);
  char line[500];
  std::snprintf(line, sizeof line,
                "tagged VACF: %d curves (time origins) of %d lags, N = %.0f particles (d = "
                "%.6f); Z(1) = %.6f +- %.2g (standard error over origins), eq 19: %.6f at that "
                "d (%.6f at the scene's d); Boltzmann D0 = %.6g (eq 20), t0 = %.6g (eq 21); "
                "eq 22 correction (1 - d)/N = %.4g",
                tagged.curves(), tagged.max_lag(), th.particles, d_lattice, z[1], e[1], z1_lattice,
                th.z1, th.d0, th.t0, th.correction);
  log.line(line);
  if (writer == nullptr)
    return;
  std::vector<double> lags, corrected;
  for (std::size_t t = 0; t < z.size(); ++t) {
    lags.push_back(static_cast<double>(t));
    corrected.push_back(z[t] + th.correction);
  }
  writer->write_result("vacf", lattice.time(), static_cast<double>(lattice.time()), z,
                       {{"lags", lags},
                        {"error", e},
                        {"corrected", corrected},
                        {"curves", {static_cast<double>(tagged.curves())}},
                        {"particles", {th.particles}},
                        {"one_step_theory", {th.z1}},
                        {"boltzmann_diffusion", {th.d0}},
                        {"mean_free_time", {th.t0}},
                        {"finite_size_correction", {th.correction}}});
  writer->flush();
}

ColloidParams colloid_params(const scene::Scene &scene) {
  const scene::LgcaColloid &c = *scene.colloid;
  ColloidParams p;
  p.x = c.x;
  p.y = c.y;
  p.radius = c.radius;
  p.mass = c.mass;
  p.vx = c.vx;
  p.vy = c.vy;
  p.held = c.held;
  p.seed_for_rules = scene.run.seed;
  return p;
}

// The colloid's VACF and (virtual, for a held disc) D(t): log lines and /observables/colloid_*
// (rank 0).
void finish_colloid(const FhpColloid &colloid, const ColloidCorrelations &stats,
                    const FhpLattice &lattice, bool closed, run::Log &log,
                    io::ObservablesWriter *writer) {
  // The eq 22 analogue M / M_tot (colloid_correlations.hpp): only where V is conserved.
  const double m_total = colloid.params().mass + static_cast<double>(total_mass(lattice));
  const double plateau = closed ? colloid.composite_mass(lattice) / m_total : 0.0;
  const auto z = stats.vacf(), d = stats.diffusion();
  const auto zc = stats.vacf(plateau), dc = stats.diffusion(plateau);
  const auto v = colloid.centre_of_mass_velocity(lattice);
  char line[700];
  const auto u = colloid.velocity();
  const auto x = colloid.position();
  std::snprintf(line, sizeof line,
                "colloid (velocity U of disc + gas inside, about the centre-of-mass velocity V "
                "= (%.3g, %.3g)): <(U - V)^2> = %.4g; final U = (%.4g, %.4g), omega %.4g, "
                "centre (%.6g, %.6g); %s; "
                "Z(%d) = %.4g +- %.2g (%.4g with the eq 22 analogue M/M_tot = %.4g); D(%d) = "
                "%.4g +- %.2g (%.4g)",
                closed ? v[0] : 0.0, closed ? v[1] : 0.0, stats.mean_square_velocity(), u[0], u[1],
                colloid.omega(), x[0], x[1],
                closed ? "fluid + colloid momentum conserved exactly (checked at every sample)"
                       : "momentum not closed (walls, obstacles or force), V taken as 0",
                static_cast<int>(z.lags.back()), z.value.back(), z.error.back(), zc.value.back(),
                plateau, static_cast<int>(d.lags.back()), d.value.back(), d.error.back(),
                dc.value.back());
  log.line(line);
  if (writer == nullptr)
    return;
  const double t = static_cast<double>(lattice.time());
  writer->write_result("colloid_vacf", lattice.time(), t, z.value,
                       {{"lags", z.lags},
                        {"error", z.error},
                        {"corrected", zc.value},
                        {"corrected_blocks", zc.blocks}, // [blocks][lags], row-major
                        {"plateau", {plateau}},
                        {"mean_square_velocity", {stats.mean_square_velocity()}}});
  writer->write_result("colloid_diffusion", lattice.time(), t, d.value,
                       {{"lags", d.lags},
                        {"error", d.error},
                        {"corrected", dc.value},
                        {"corrected_blocks", dc.blocks}});
  writer->flush();
}

} // namespace

FhpModel fhp_model(scene::LgcaModel m) {
  switch (m) {
  case scene::LgcaModel::fhp_i:
    return FhpModel::fhp_i;
  case scene::LgcaModel::fhp_ii:
    return FhpModel::fhp_ii;
  case scene::LgcaModel::fhp_iii:
    return FhpModel::fhp_iii;
  case scene::LgcaModel::fhp_saturated:
    return FhpModel::fhp_saturated;
  case scene::LgcaModel::dhumieres_1d:
    break;
  }
  throw input_error("lattice.model = \"dhumieres-1d\" is not an FHP model");
}

FhpParams fhp_params(const scene::Scene &scene) {
  const scene::Lgca &g = *scene.lgca;
  FhpParams p;
  p.model = fhp_model(g.model);
  p.size_x = static_cast<int>(g.size.at(0));
  p.size_y = static_cast<int>(g.size.at(1));
  p.seed = scene.run.seed;
  p.walls = g.walls;
  p.force = g.body_force;
  for (const auto &o : g.obstacles)
    p.obstacles.push_back({o.x, o.y, o.radius});
  return p;
}

std::vector<std::string> describe(const scene::Scene &scene, MPI_Comm comm) {
  const scene::Lgca &g = *scene.lgca;
  std::vector<std::string> out;
  if (g.model == scene::LgcaModel::dhumieres_1d) {
    const double n = static_cast<double>(g.size.at(0)) * dhumieres::links * g.density;
    out.push_back("engine lgca: d'Humieres 1D model (velocities 0, +-1, +-2; collisions swap "
                  "the two states of a (mass, momentum) class) on a ring of " +
                  std::to_string(g.size.at(0)) + " sites, d = " + fmt("%.6g", g.density) +
                  " per link, N = " + fmt("%.0f", n) + " particles");
    if (scene.tagged) {
      const int curves = static_cast<int>(scene.run.steps / scene.tagged->max_lag);
      const bool p0 = g.initial == scene::LgcaInitial::zero_momentum;
      out.push_back(std::string("initial: ") +
                    (p0 ? "zero-momentum (exactly N particles and P = 0, the {N, P} ensemble)"
                        : "equilibrium (independent occupations d)") +
                    "; tagged VACF lags 0.." + std::to_string(scene.tagged->max_lag) + ", " +
                    std::to_string(curves) + " curves per replica, " +
                    std::to_string(scene.tagged->replicas) +
                    " replica(s) spread over the ranks; plateau (eq 22) " +
                    fmt("%.4g", p0 ? -theory::finite_size_correction(g.density, n) : 0.0));
    }
    return out;
  }
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const FhpModel m = fhp_model(g.model);
  const std::int64_t X = g.size[0], Y = g.size[1];
  out.push_back(std::string("engine lgca: ") + to_string(m) + " (" + std::to_string(links(m)) +
                " links per site) on a " + std::to_string(X) + " x " + std::to_string(Y) +
                " triangular lattice (" + std::to_string(X * Y) + " sites, rows sqrt(3)/2 apart, " +
                "L_y = " + fmt("%.6g", Y * sqrt3_2) + "), periodic in x" +
                (g.walls
                     ? ", no-slip walls (solid rows y = 0 and y = " + std::to_string(Y - 1) + ")"
                     : " and y"));
  const double nu = boltzmann_viscosity(m, g.density);
  const double nu_table = table_viscosity(make_collision_table(m), g.density);
  out.push_back("density d = " + fmt("%.6g", g.density) + " per link (" +
                fmt("%.6g", links(m) * g.density) + " particles per site); Boltzmann viscosity " +
                fmt("%.6g", nu) + " (PHYSICS.md), " + fmt("%.6g", nu_table) +
                " from the collision table");
  if (g.initial == scene::LgcaInitial::shear_wave) {
    const double k = two_pi / (Y * sqrt3_2);
    out.push_back("initial: shear wave u_x = " + fmt("%.4g", g.amplitude) +
                  " sin(2 pi y / L_y); Boltzmann decay rate nu k^2 = " + fmt("%.6g", nu * k * k) +
                  " per step (1/e after " + fmt("%.4g", 1.0 / (nu * k * k)) + " steps)");
  } else {
    out.push_back("initial: equilibrium (every link occupied with probability d)");
  }
  if (scene.tagged) {
    const TaggedTheory th = tagged_theory(m, g.density, static_cast<double>(X * Y));
    out.push_back("tagged VACF (moment propagation, weight split equally over the outgoing "
                  "particles): lags 0.." +
                  std::to_string(scene.tagged->max_lag) +
                  ", successive time origins; eq 19 Z(1) = " + fmt("%.6g", th.z1) +
                  ", eq 20 Boltzmann D0 = " + fmt("%.6g", th.d0) +
                  ", eq 21 mean free time t0 = " + fmt("%.6g", th.t0) +
                  ", eq 22 correction (1 - d)/N = " + fmt("%.4g", th.correction) +
                  " (N = " + fmt("%.0f", th.particles) + " expected)");
  }
  if (scene.colloid) {
    const scene::LgcaColloid &c = *scene.colloid;
    out.push_back(std::string("colloid (") +
                  (c.held ? "held in place" : "moving, centre advanced by U every step") +
                  ", Ladd-Frenkel moving-boundary rules eq 23-27, replicated on every rank): "
                  "disc of radius " +
                  fmt("%.4g", c.radius) + " at (" + fmt("%.6g", c.x) + ", " + fmt("%.6g", c.y) +
                  "), mass " + fmt("%.6g", c.mass) + ", initial velocity (" + fmt("%.4g", c.vx) +
                  ", " + fmt("%.4g", c.vy) + "); velocity VACF lags 0.." +
                  std::to_string(c.max_lag) + ", virtual displacement D(t) every " +
                  std::to_string(c.displacement_every) + " up to " +
                  std::to_string(c.displacement_lag));
  }
  if (g.body_force > 0.0)
    out.push_back("body force: a particle moves from link 3 (-x) to link 0 (+x) with "
                  "probability " +
                  fmt("%.4g", g.body_force) + " per fluid site and step");
  if (!g.obstacles.empty())
    out.push_back(std::to_string(g.obstacles.size()) + " solid disc(s) (bounce-back)");
  out.push_back(std::string("kernel: ") +
                (vbmi_kernel() ? "AVX-512 VBMI byte permutes, 64 sites per instruction"
                               : "portable table look-up") +
                "; chirality bits from Philox (seed, step, row, 128 columns)");
  const double bytes = static_cast<double>(X * Y) * ((g.walls || !g.obstacles.empty()) ? 3 : 2);
  out.push_back(std::to_string(ranks) + " rank(s): slabs of about " + std::to_string(X / ranks) +
                " columns, memory about " + fmt("%.3g", bytes / ranks / 1048576.0) +
                " MiB per rank");
  out.push_back("run: " + std::to_string(scene.run.steps) + " steps, observables every " +
                std::to_string(scene.output.every) + " steps, fields in blocks of " +
                std::to_string(g.block) + " x " + std::to_string(g.block) + " sites");
  return out;
}

namespace {

// The 1D model: independent replicas (own initial state and collision seed) spread over the
// ranks, each `steps / max_lag` successive VACF curves; rank 0 averages the normalised curves
// in replica order (bitwise the same on any number of ranks), the error is the spread of the
// replicas. Its one step is the whole measurement of this rank's replicas (asking for stop
// signals every 4096 lattice steps); it keeps no checkpoints.
class DhumieresEngine final : public run::Engine {
public:
  DhumieresEngine(const scene::Scene &scene, const run::Options &options, MPI_Comm comm)
      : scene_(scene), comm_(comm), g_(*scene.lgca), L_(g_.size.at(0)),
        max_lag_(static_cast<int>(scene.tagged->max_lag)),
        replicas_(static_cast<int>(scene.tagged->replicas)),
        curves_(static_cast<int>(scene.run.steps / max_lag_)),
        row_(static_cast<std::size_t>(max_lag_) + 3) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
    if (!options.restart.empty())
      throw input_error(scene.file + ": --restart is not available for lattice.model = "
                                     "\"dhumieres-1d\" (no checkpoints); allowed: a fresh run");
    if (curves_ < 1)
      throw input_error(scene.file + ": run.steps = " + std::to_string(scene.run.steps) +
                        " is shorter than tagged.max_lag = " + std::to_string(max_lag_) +
                        "; allowed: run.steps >= tagged.max_lag");
  }

  run::RunSpan span() const override { return {scene_.run.steps, "run.steps", {}}; }
  void start(run::Shell &shell) override { shell_ = &shell; }
  void open(run::Shell &, run::Log &log) override {
    for (const auto &line : describe(scene_, comm_))
      log.line(line);
  }
  std::int64_t step() const override { return step_; }

  // Row k of mine_: Z(0..max_lag) of replica k, then N and P.
  bool advance() override {
    const auto ensemble = ensemble_of();
    mine_.assign(row_ * replicas_, 0.0);
    const auto stop = [&] { return shell_->stop_received(); };
    int interrupted = 0;
    for (int k = rank_; k < replicas_ && !shell_->stop_received(); k += ranks_) {
      const auto r = dhumieres::measure_vacf(L_, g_.density, ensemble, dhumieres::Rule::swap,
                                             scene_.run.seed + 1000 * static_cast<std::uint64_t>(k),
                                             max_lag_, curves_, stop);
      if (r.stopped)
        break;
      for (int t = 0; t <= max_lag_; ++t)
        mine_[k * row_ + t] = r.vacf[t] / r.vacf[0];
      mine_[k * row_ + max_lag_ + 1] = static_cast<double>(r.particles);
      mine_[k * row_ + max_lag_ + 2] = static_cast<double>(r.momentum);
    }
    interrupted = shell_->stop_received() != 0 ? 1 : 0;
    int any = 0;
    MPI_Allreduce(&interrupted, &any, 1, MPI_INT, MPI_MAX, comm_);
    if (any)
      return false;
    step_ = scene_.run.steps;
    return true;
  }
  void observe() override {}
  std::string write_checkpoint(run::Shell &, const std::string &) override {
    throw std::logic_error("lattice.model = \"dhumieres-1d\" keeps no checkpoints");
  }
  bool keeps_checkpoints() const override { return false; }
  run::Progress progress() const override { return {}; }

  void finish(run::Log &log, const run::Loop &loop) override {
    if (loop.stopped)
      log.line("stopped by a signal before every curve was measured: lattice.model = "
               "\"dhumieres-1d\" keeps no checkpoints, so no result is written; exit 0 (run it "
               "again, or with fewer tagged.replicas or run.steps)");
  }

  // Every entry has one non-zero contribution: the sum is exact.
  void summary(run::Log &log, const run::Loop &) override {
    const int max_lag = max_lag_, replicas = replicas_;
    const std::size_t row = row_;
    std::vector<double> all(row * replicas, 0.0);
    MPI_Reduce(mine_.data(), all.data(), static_cast<int>(all.size()), MPI_DOUBLE, MPI_SUM, 0,
               comm_);
    if (rank_ != 0)
      return;
    std::vector<double> z(max_lag + 1, 0.0), e(max_lag + 1, 0.0), lags;
    double n = 0.0;
    for (int k = 0; k < replicas; ++k)
      n += all[k * row + max_lag + 1] / replicas;
    for (int t = 0; t <= max_lag; ++t) {
      for (int k = 0; k < replicas; ++k)
        z[t] += all[k * row + t] / replicas;
      double v = 0.0;
      for (int k = 0; k < replicas; ++k)
        v += (all[k * row + t] - z[t]) * (all[k * row + t] - z[t]);
      e[t] = replicas > 1 ? std::sqrt(v / (replicas - 1) / replicas) : 0.0;
      lags.push_back(t);
    }
    const bool p0 = ensemble_of() == dhumieres::Ensemble::zero_momentum;
    const double plateau = p0 ? -theory::finite_size_correction(g_.density, n) : 0.0;
    // the plateau window: after the tagged particle's own decay (t ~ 20), before the sound
    // pulses come back around the ring (t < L / c_s, c_s = sqrt 2)
    const int t1 = std::min(20, max_lag),
              t2 = std::max(t1, std::min(max_lag, static_cast<int>(0.6 * L_ / std::sqrt(2.0))));
    double w = 0.0, we = 0.0;
    for (int t = t1; t <= t2; ++t) {
      w += z[t] / (t2 - t1 + 1);
      we += e[t] / (t2 - t1 + 1);
    }
    char line[400];
    std::snprintf(line, sizeof line,
                  "tagged VACF: %d replica(s) x %d curves of %d lags, N = %.0f; Z(1) = %.6f +- "
                  "%.2g, eq 19 (b = 5): %.6f; plateau over lags %d..%d: %.4g (eq 22: %.4g), "
                  "error of one lag about %.2g",
                  replicas, curves_, max_lag, n, z[1], e[1],
                  theory::one_step_vacf(dhumieres::link_velocities(), g_.density), t1, t2, w,
                  plateau, we);
    log.line(line);
    io::ObservablesWriter writer(shell_->output_file("observables"), scene_.text);
    const std::int64_t steps = measured_steps();
    writer.write_result("vacf", steps, static_cast<double>(steps), z,
                        {{"lags", lags},
                         {"error", e},
                         {"particles", {n}},
                         {"density", {g_.density}},
                         {"L", {static_cast<double>(L_)}},
                         {"replicas", {static_cast<double>(replicas)}},
                         {"plateau_theory", {plateau}},
                         {"plateau", {w}},
                         {"window", {static_cast<double>(t1), static_cast<double>(t2)}}});
    writer.flush();
  }

  run::LoopTime loop_time(const run::Loop &loop) const override {
    const std::int64_t steps = loop.stopped ? 0 : measured_steps();
    const double updates = static_cast<double>(steps) * static_cast<double>(L_) * replicas_;
    return {static_cast<std::uint64_t>(steps), "steps", std::to_string(L_ * replicas_) + " sites",
            updates, "site-updates"};
  }

private:
  dhumieres::Ensemble ensemble_of() const {
    return g_.initial == scene::LgcaInitial::zero_momentum ? dhumieres::Ensemble::zero_momentum
                                                           : dhumieres::Ensemble::independent;
  }
  std::int64_t measured_steps() const { return static_cast<std::int64_t>(curves_) * max_lag_; }

  const scene::Scene &scene_;
  MPI_Comm comm_;
  const scene::Lgca &g_;
  std::int64_t L_;
  int max_lag_, replicas_, curves_;
  std::size_t row_;
  int rank_ = 0, ranks_ = 1;
  run::Shell *shell_ = nullptr;
  std::int64_t step_ = 0;
  std::vector<double> mine_;
};

// An FHP lattice (with a colloid, tagged particles) in the run loop.
class FhpEngine final : public run::Engine {
public:
  // The lattice first: a decomposition the lattice cannot take is refused before any output.
  FhpEngine(const scene::Scene &scene, MPI_Comm comm)
      : scene_(scene), comm_(comm), lattice_(fhp_params(scene), comm),
        sites_(static_cast<std::int64_t>(lattice_.size_x()) * lattice_.size_y()) {
    if (scene.colloid)
      colloid_ = std::make_unique<FhpColloid>(colloid_params(scene), lattice_);
  }

  run::RunSpan span() const override { return {scene_.run.steps, "run.steps", {}}; }

  // The state, from the scene or the checkpoint (every rank agrees on a refusal) before
  // anything is written.
  void start(run::Shell &shell) override {
    if (shell.restarting()) {
      const std::string &restart_file = shell.restart_file();
      run::collectively(comm_, [&] {
        read_lattice_checkpoint(restart_file, shell.restart_info(), lattice_);
        if (colloid_) {
          stored_colloid_ = read_colloid_checkpoint(restart_file, lattice_, colloid_->params());
          colloid_->set_state(stored_colloid_.momentum, stored_colloid_.omega,
                              stored_colloid_.position, stored_colloid_.angle);
        }
      });
    } else {
      lattice_.initialise(scene_.lgca->density, scene_.lgca->amplitude);
    }
  }

  void open(run::Shell &shell, run::Log &log) override {
    const scene::Scene &scene = scene_;
    const bool restarting = shell.restarting();
    const std::string &restart_file = shell.restart_file();
    for (const auto &line : describe(scene, comm_))
      log.line(line);
    if (restarting)
      log.line("restarted from " + restart_file + " at step " + std::to_string(lattice_.time()));
    std::unique_ptr<io::ObservablesWriter> writer;
    if (shell.rank() == 0)
      writer =
          std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene.text);
    writer_ = writer.get();
    observer_.emplace(scene, lattice_, std::move(writer));
    if (!restarting)
      observer_->sample(lattice_); // the initial shear wave belongs to the decay curve
    // The tagged VACF starts afresh at the first step of this run (also after a restart).
    if (scene.tagged) {
      tagged_ = std::make_unique<FhpTagged>(lattice_, static_cast<int>(scene.tagged->max_lag));
      tagged_->feed(lattice_);
    }

    mass_ = total_mass(lattice_);
    // Fluid + colloid momentum is conserved exactly without walls, obstacles and body force.
    closed_ = colloid_ && !scene.lgca->walls && scene.lgca->obstacles.empty() &&
              scene.lgca->body_force == 0.0;
    if (closed_)
      momentum0_ = total_momentum();
    // The colloid averages are of U - V, V the conserved centre-of-mass velocity (see
    // colloid_correlations.hpp); V is not conserved with walls, obstacles or a force: then V
    // = 0.
    if (colloid_)
      colloid_stats_ = std::make_unique<ColloidCorrelations>(
          static_cast<int>(scene.colloid->max_lag),
          static_cast<int>(scene.colloid->displacement_lag),
          static_cast<int>(scene.colloid->displacement_every), scene.run.steps - lattice_.time(),
          closed_ ? colloid_->centre_of_mass_velocity(lattice_) : std::array<double, 2>{0.0, 0.0});
    // A restart with the checkpoint's run.steps continues the colloid averages of the
    // checkpoint (the same as one long run); another run.steps starts a new averaging run (e.g.
    // after an equilibration job), as does a checkpoint without averages or of other lags.
    if (colloid_stats_ && restarting) {
      const std::int64_t stored_steps =
          scene::parse_scene(shell.restart_info().scene_text, restart_file + ":/parameters/scene")
              .run.steps;
      if (stored_steps != scene.run.steps)
        log.line("colloid VACF and D(t) start afresh (run.steps = " +
                 std::to_string(scene.run.steps) + ", the checkpoint's run had " +
                 std::to_string(stored_steps) + ": a new averaging run)");
      else if (colloid_stats_->restore(stored_colloid_.correlations))
        log.line("colloid VACF and D(t) continue the averages of the checkpoint");
      else
        log.line("colloid VACF and D(t) start afresh (the checkpoint has no averages of these "
                 "lags)");
    }
  }

  std::int64_t step() const override { return lattice_.time(); }

  bool advance() override {
    if (colloid_)
      colloid_->apply(lattice_);
    lattice_.step();
    if (colloid_stats_)
      colloid_stats_->add(colloid_->composite_velocity(lattice_));
    observer_->every_step(lattice_);
    if (tagged_)
      tagged_->feed(lattice_);
    return true;
  }

  void observe() override {
    const std::int64_t now = total_mass(lattice_);
    if (now != mass_)
      throw invariant_error("lattice mass changed from " + std::to_string(mass_) + " to " +
                            std::to_string(now) + " at step " + std::to_string(lattice_.time()));
    if (closed_ && total_momentum() != momentum0_)
      throw invariant_error("fluid + colloid momentum changed at step " +
                            std::to_string(lattice_.time()));
    observer_->sample(lattice_);
  }

  std::string write_checkpoint(run::Shell &shell, const std::string &path) override {
    Stopwatch watch;
    const double bytes = write_lattice_checkpoint(path, lattice_, scene_.text, scene_.canonical);
    if (colloid_ && shell.rank() == 0)
      write_colloid_checkpoint(path, *colloid_, colloid_stats_.get());
    char text[120];
    std::snprintf(text, sizeof text, "%.1f MB of lattice in %.3g s", bytes / 1e6, watch.seconds());
    return text;
  }

  run::Progress progress() const override {
    return {static_cast<double>(sites_), "site-updates/s"};
  }

  void finish(run::Log &log, const run::Loop &) override {
    if (tagged_)
      finish_vacf(scene_, lattice_, *tagged_, log, writer_);
    if (colloid_stats_)
      finish_colloid(*colloid_, *colloid_stats_, lattice_, closed_, log, writer_);
  }

  run::LoopTime loop_time(const run::Loop &loop) const override {
    const auto steps = static_cast<std::uint64_t>(loop.steps);
    return {steps, "steps", std::to_string(sites_) + " sites",
            static_cast<double>(steps) * static_cast<double>(sites_), "site-updates"};
  }

private:
  MomentumUnits total_momentum() const {
    MomentumUnits p = fluid_momentum(lattice_);
    p[0] += colloid_->momentum()[0];
    p[1] += colloid_->momentum()[1];
    return p;
  }

  const scene::Scene &scene_;
  MPI_Comm comm_;
  FhpLattice lattice_;
  std::int64_t sites_;
  std::unique_ptr<FhpColloid> colloid_;
  ColloidCheckpoint stored_colloid_;        // a restart's colloid, for its averages
  io::ObservablesWriter *writer_ = nullptr; // rank 0's, owned by the observer
  std::optional<Observer> observer_;
  std::unique_ptr<FhpTagged> tagged_;
  std::int64_t mass_ = 0;
  bool closed_ = false;
  MomentumUnits momentum0_{};
  std::unique_ptr<ColloidCorrelations> colloid_stats_;
};

} // namespace

std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm) {
  refuse_unavailable(scene);
  // The decomposition is checked here too, so `check` refuses what `run` would.
  if (scene.lgca->model != scene::LgcaModel::dhumieres_1d) {
    const parallel::Slabs slabs(comm, static_cast<int>(scene.lgca->size.at(0)), 2);
  }
  return describe(scene, comm);
}

std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &options,
                                         MPI_Comm comm) {
  refuse_unavailable(scene);
  if (scene.lgca->model == scene::LgcaModel::dhumieres_1d)
    return std::make_unique<DhumieresEngine>(scene, options, comm);
  return std::make_unique<FhpEngine>(scene, comm);
}

void run_bench(std::ostream &out, int n, int steps, bool json, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  FhpParams p;
  p.model = FhpModel::fhp_iii;
  p.size_x = n;
  p.size_y = n + n % 2;
  p.seed = 1;
  const double sites = static_cast<double>(p.size_x) * p.size_y;
  const auto time_steps = [&](MPI_Comm c) {
    FhpLattice l(p, c);
    l.initialise(0.3, 0.0);
    for (int i = 0; i < 3; ++i)
      l.step();
    MPI_Barrier(c);
    Stopwatch clock;
    for (int i = 0; i < steps; ++i)
      l.step();
    MPI_Barrier(c);
    return clock.seconds();
  };
  // The other ranks wait for rank 0's one-rank timing asleep: a busy-polling MPI_Bcast would
  // take a core from it when ranks share cores.
  double one = 0.0;
  if (rank == 0)
    one = time_steps(MPI_COMM_SELF);
  MPI_Request request;
  MPI_Ibcast(&one, 1, MPI_DOUBLE, 0, comm, &request);
  for (int done = 0; !done;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const double all = ranks > 1 ? time_steps(comm) : one;
  if (rank != 0)
    return;
  const double rate1 = sites * steps / one, rate_p = sites * steps / all;
  if (json) {
    out << "{\"lgca\": {\"model\": \"fhp-iii\", \"size\": [" << p.size_x << ", " << p.size_y
        << "], \"steps\": " << steps << ", \"kernel\": \"" << (vbmi_kernel() ? "vbmi" : "portable")
        << "\", \"site_updates_per_s_one_rank\": " << rate1 << ", \"ranks\": " << ranks
        << ", \"site_updates_per_s\": " << rate_p << ", \"per_core\": " << rate_p / ranks
        << ", \"speedup\": " << rate_p / rate1 << "}}\n";
    return;
  }
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "lgca fhp-iii %d x %d, %d steps, %s kernel: 1 rank %.3g site-updates/s; %d "
                "ranks %.3g site-updates/s (%.3g per core), speedup %.2f",
                p.size_x, p.size_y, steps, vbmi_kernel() ? "AVX-512 VBMI" : "portable", rate1,
                ranks, rate_p, rate_p / ranks, rate_p / rate1);
  out << buf << '\n';
}

} // namespace narrows::lgca
