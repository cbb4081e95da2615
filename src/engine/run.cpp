// The run loop: step the pipeline, observe on a schedule, check invariants, report progress.
#include "narrows/engine/run.hpp"

#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/analysis/poiseuille.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engine/info.hpp"
#include "narrows/engine/invariants.hpp"
#include "narrows/engine/log.hpp"
#include "narrows/engine/mpcd_simulation.hpp"
#include "narrows/engine/totals.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/colloid_checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/io/trajectory_writer.hpp"
#include "narrows/parallel/slabs.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace narrows::engine {

namespace {

bool wants(const scene::Scene &s, const std::string &name) {
  const auto &o = s.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

// Everything written every `output.every` steps.
class Observer {
public:
  Observer(MpcdSimulation &sim, std::unique_ptr<io::ObservablesWriter> writer)
      : sim_(sim), writer_(std::move(writer)), profiles_(sim.box()) {
    const auto &s = sim.scene();
    temperature_ = wants(s, "temperature");
    momentum_ = wants(s, "momentum");
    velocity_ = wants(s, "velocity_profile");
    density_ = wants(s, "density_profile");
    viscosity_ = wants(s, "viscosity");
    energy_ = wants(s, "energy");
    settling_ = wants(s, "settling_velocity");
    positions_ = wants(s, "colloid_positions");
  }
  void every_step() {
    if (velocity_ || density_ || viscosity_)
      profiles_.add(sim_.fluid());
    if (settling_)
      settling_sum_.add(sim_);
  }
  void sample() {
    const auto step = sim_.step();
    const double t = sim_.time();
    const MPI_Comm comm = sim_.comm();
    if (temperature_) {
      const double kT = analysis::temperature(sim_.fluid(), comm);
      if (writer_)
        writer_->append_scalar("temperature", step, t, kT);
    }
    if (energy_) {
      const double e = total_energy(sim_);
      if (writer_)
        writer_->append_scalar("energy", step, t, e);
    }
    if (settling_) {
      const auto v = settling_sum_.mean();
      if (writer_)
        writer_->append_vector("settling_velocity", step, t, std::span(v.data(), sim_.box().dim));
      settling_sum_ = SettlingSum{};
    }
    if (positions_ && writer_) {
      const auto &c = sim_.colloids();
      const int d = c.dim;
      std::vector<double> ids(c.size()), x(c.size() * d);
      for (std::size_t a = 0; a < c.size(); ++a) {
        ids[a] = static_cast<double>(c.id[a]);
        for (int k = 0; k < d; ++k)
          x[a * d + k] = c.x[k][a];
      }
      writer_->append_profile("colloid_positions", step, t, ids, x, d);
    }
    if (momentum_) {
      const auto p = total_momentum(sim_);
      if (writer_)
        writer_->append_vector("momentum", step, t, std::span(p.data(), sim_.box().dim));
    }
    if (velocity_ || density_ || viscosity_) {
      std::vector<double> v, rho;
      if (profiles_.finish(comm, v, rho) && writer_) {
        if (viscosity_) {
          const auto &sc = sim_.scene();
          const auto fit = analysis::fit_poiseuille(profiles_.bin_centres(), v, sim_.box().dim,
                                                    profiles_.bin_width(), sim_.box().length[1],
                                                    sc.body_force->value[0]);
          writer_->append_scalar("viscosity", step, t, fit.nu);
        }
        if (velocity_)
          writer_->append_profile("velocity_profile", step, t, profiles_.bin_centres(), v,
                                  sim_.box().dim);
        if (density_)
          writer_->append_profile("density_profile", step, t, profiles_.bin_centres(), rho, 1);
      }
    }
    if (writer_)
      writer_->flush();
  }

private:
  MpcdSimulation &sim_;
  std::unique_ptr<io::ObservablesWriter> writer_;
  analysis::ProfileAccumulator profiles_;
  SettlingSum settling_sum_;
  bool temperature_ = false, momentum_ = false, velocity_ = false, density_ = false,
       viscosity_ = false, energy_ = false, settling_ = false, positions_ = false;
};

} // namespace

void run_scene(const scene::Scene &scene, const RunOptions &options, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // Refuse a decomposition the box cannot take before anything is written.
  check_ranks(scene, comm);
  // A restart is checked (file, format, scene) before anything is written.
  std::string restart_file;
  io::CheckpointInfo restart_info;
  if (!options.restart.empty()) {
    restart_file = io::resolve_restart(options.restart);
    restart_info = io::read_checkpoint_info(restart_file, comm);
    io::check_restart_scene(scene, restart_info, restart_file);
  }
  const bool restarting = !restart_file.empty();
  if (!restarting)
    check_colloid_placement(scene);

  const std::string dir = options.out_dir.empty() ? scene.output.dir : options.out_dir;
  RunOutput output = open_run_output(dir, restarting ? restart_info.step : -1, scene.file, comm);
  Log &log = output.log;
  const std::string &from = output.suffix;
  for (const auto &line : describe_scene(scene, comm))
    log.line(line);
  for (const auto &w : regime_warnings(scene))
    log.warn(w);

  MpcdSimulation sim(scene, comm, !restarting);
  if (restarting) {
    sim.restore(io::read_fluid(restart_file, restart_info, comm), restart_info.step);
    if (scene.colloids)
      sim.restore_colloids(io::read_colloids(restart_file, *scene.colloids, scene.run.dimensions,
                                             scene.fluid.density, scene.run.seed, comm));
    log.line("restarted from " + restart_file + " at step " + std::to_string(sim.step()));
  }
  std::unique_ptr<io::ObservablesWriter> writer;
  if (rank == 0)
    writer =
        std::make_unique<io::ObservablesWriter>(dir + "/observables" + from + ".h5", scene.text);
  Observer observer(sim, std::move(writer));
  std::optional<io::TrajectoryWriter> trajectory;
  const colloids::Colloids *colloids = scene.colloids ? &sim.colloids() : nullptr;
  const std::int64_t frame_every = scene.output.trajectory_every;
  if (frame_every > 0) {
    trajectory.emplace(
        dir + "/trajectory" + from + ".h5", scene.text, sim.box(), particle_count(scene),
        static_cast<std::uint64_t>(scene.output.trajectory_subsample), comm, colloids);
    log.line("trajectory: " + std::to_string(trajectory->tracked()) + " fluid particles" +
             (colloids ? " and " + std::to_string(colloids->size()) + " colloids" : "") +
             " every " + std::to_string(frame_every) + " steps to " + dir + "/trajectory" + from +
             ".h5 (ParaView: trajectory" + from + ".xdmf)");
    if (!restarting)
      trajectory->write_frame(sim.step(), sim.time(), sim.fluid(), colloids);
  }
  const InvariantCheck invariants(sim);
  const std::int64_t every = scene.output.every;
  const auto n_particles = analysis::total_momentum(sim.fluid(), comm).count;

  // Checkpoints: every output.checkpoint_every steps, at the end, and on SIGTERM/SIGUSR1.
  auto save_checkpoint = [&] {
    Stopwatch watch;
    io::CheckpointInfo info{scene.text,    sim.step(),       sim.time(), scene.run.seed,
                            sim.box().dim, sim.box().length, false};
    info.walls_y = sim.box().walls_y;
    const std::string path = io::checkpoint_path(dir, sim.step());
    std::vector<io::SpeciesFields> species{io::fluid_fields(sim.fluid())};
    colloids::Colloids none;
    if (scene.colloids)
      species.push_back(io::colloid_fields(sim.colloids(), none, comm));
    const double bytes = io::write_checkpoint(path, info, species, comm);
    if (rank == 0)
      io::prune_checkpoints(dir, scene.output.checkpoint_keep);
    const double s = watch.seconds();
    char line[300];
    std::snprintf(line, sizeof line, "checkpoint %s: %.1f MB of particles in %.3g s (%.1f MB/s)",
                  path.c_str(), bytes / 1e6, s, s > 0 ? bytes / 1e6 / s : 0.0);
    log.line(line);
    return path;
  };
  const io::StopSignals signals;
  int stop = 0;

  Stopwatch clock, since_progress;
  const std::int64_t first = sim.step();
  while (sim.step() < scene.run.steps) {
    sim.advance();
    observer.every_step();
    if (sim.step() % every == 0 || sim.step() == scene.run.steps) {
      invariants.check(sim);
      observer.sample();
    }
    if (trajectory && sim.step() % frame_every == 0)
      trajectory->write_frame(sim.step(), sim.time(), sim.fluid(), colloids);
    if ((stop = signals.requested(comm)) != 0)
      break;
    const std::int64_t cadence = scene.output.checkpoint_every;
    if (cadence > 0 && sim.step() % cadence == 0 && sim.step() < scene.run.steps)
      save_checkpoint();
    if (scene.output.progress && since_progress.seconds() > 10.0) {
      since_progress.restart();
      log.line(progress_line(sim.step(), first, scene.run.steps, clock.seconds(),
                             static_cast<double>(n_particles), "particle-steps/s"));
    }
  }
  const double seconds = clock.seconds();
  const auto steps = sim.step() - first;
  const std::string last = save_checkpoint();
  if (stop != 0)
    log.line(std::string("received ") + io::signal_name(stop) + ": stopped after step " +
             std::to_string(sim.step()) + ", checkpoint " + last +
             " written; exit 0 (continue with --restart " + dir + ")");
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "Loop time of %.4g s on %d ranks for %lld steps with %llu particles (%.4g "
                "particle-steps/s)",
                seconds, ranks, static_cast<long long>(steps),
                static_cast<unsigned long long>(n_particles),
                seconds > 0 ? static_cast<double>(steps) * n_particles / seconds : 0.0);
  log.line(buf);
}

} // namespace narrows::engine
