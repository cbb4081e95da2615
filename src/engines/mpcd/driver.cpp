// The MPCD engine of the run loop: the simulation's step, observables on a schedule, invariant
// checks, trajectory frames, checkpoints of fluid, colloids and contacts, the closing lines.
#include "narrows/engines/mpcd/driver.hpp"

#include "narrows/analysis/contact_statistics.hpp"
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/analysis/poiseuille.hpp"
#include "narrows/colloids/contact_network.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/axial_fields.hpp"
#include "narrows/engines/mpcd/colloid_checkpoint.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"
#include "narrows/engines/mpcd/colloid_statistics.hpp"
#include "narrows/engines/mpcd/fluid_checkpoint.hpp"
#include "narrows/engines/mpcd/info.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/restart_checks.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/engines/mpcd/totals.hpp"
#include "narrows/engines/mpcd/trajectory_writer.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/parallel/message_clock.hpp"
#include "narrows/parallel/slabs.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/run/engine.hpp"
#include "narrows/run/shell.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace narrows::mpcd {

namespace {

bool wants(const scene::Scene &s, const std::string &name) {
  const auto &o = s.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

// Everything written every `output.every` steps.
class Observer {
public:
  Observer(MpcdSimulation &sim, std::unique_ptr<io::ObservablesWriter> writer,
           ColloidStatistics colloid_stats)
      : sim_(sim), writer_(std::move(writer)), profiles_(sim.box()),
        colloid_stats_(std::move(colloid_stats)) {
    const auto &s = sim.scene();
    temperature_ = wants(s, "temperature");
    momentum_ = wants(s, "momentum");
    velocity_ = wants(s, "velocity_profile");
    density_ = wants(s, "density_profile");
    viscosity_ = wants(s, "viscosity");
    energy_ = wants(s, "energy");
    settling_ = wants(s, "settling_velocity");
    positions_ = wants(s, "colloid_positions");
    contacts_ = wants(s, "contact_statistics");
    if (wants(s, "axial_fields"))
      axial_.emplace(sim.box(), s.output.axial_bin);
  }
  void every_step() {
    colloid_stats_.after_step(sim_);
    if (velocity_ || density_ || viscosity_)
      profiles_.add(sim_.fluid());
    if (settling_)
      settling_sum_.add(sim_);
  }
  void sample() {
    const auto step = sim_.step();
    const double t = sim_.time();
    const MPI_Comm comm = sim_.comm();
    colloid_stats_.on_observe(sim_, writer_.get());
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
    if (positions_) {
      const colloids::Colloids c = sim_.gather_colloids(); // collective
      const int d = c.dim;
      std::vector<double> ids(c.size()), x(c.size() * d);
      for (std::size_t a = 0; a < c.size(); ++a) {
        ids[a] = static_cast<double>(c.id[a]);
        for (int k = 0; k < d; ++k)
          x[a * d + k] = c.x[k][a];
      }
      if (writer_)
        writer_->append_profile("colloid_positions", step, t, ids, x, d);
    }
    if (contacts_)
      sample_contacts(step, t);
    if (axial_) {
      Stopwatch watch;
      const colloids::Colloids c = sim_.gather_colloids(); // collective
      const AxialSample a = axial_->sample(c, sim_.fluid(), comm);
      axial_seconds_ += watch.seconds();
      ++axial_samples_;
      if (writer_)
        writer_->append_profiles(
            "axial_fields", step, t, axial_->centres(),
            {{"phi", a.phi}, {"velocity", a.velocity}, {"fluid_velocity", a.fluid_velocity}});
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
  // The colloid statistics' sums for a checkpoint.
  std::vector<io::CheckpointArray> checkpoint_arrays() const {
    return colloid_stats_.checkpoint_arrays();
  }
  // axial_fields: the bins (for the trajectory's voronoi_fraction), and what a sample cost
  // (seconds per sample on this rank, gathering included), or nullptr / 0.
  const AxialFields *axial() const { return axial_ ? &*axial_ : nullptr; }
  double axial_seconds_per_sample() const {
    return axial_samples_ > 0 ? axial_seconds_ / static_cast<double>(axial_samples_) : 0.0;
  }
  // evolution's steady-state line (rank 0; empty without it).
  std::string steady_line() const { return colloid_stats_.steady_line(); }
  std::string window_cost_line() const { return colloid_stats_.window_cost_line(); }
  // When the run ends: the results of the whole run (colloid statistics).
  void finish() {
    if (writer_ && colloid_stats_.active()) {
      colloid_stats_.write(*writer_, sim_.step(), sim_.time());
      writer_->flush();
    }
  }

private:
  // contact_statistics: every colloid and contact gathered (each contact is held once, by the
  // rank of its owner colloid), so the sample is the same on any number of ranks.
  void sample_contacts(std::int64_t step, double t) {
    const colloids::Colloids c = sim_.gather_colloids();       // collective
    const colloids::ContactHistory h = sim_.gather_contacts(); // collective
    if (!writer_)
      return;
    const auto &spec = *sim_.scene().colloids;
    const colloids::ContactNetwork net =
        colloids::contact_network(c, h, sim_.box(), sim_.plan().no_slip_params.spring);
    std::vector<std::size_t> kinds(c.size());
    for (std::size_t a = 0; a < c.size(); ++a)
      kinds[a] = spec.kind_of(c.id[a]);
    const analysis::ContactStatistics st =
        analysis::contact_statistics(net, c.id, kinds, spec.kind_count());
    using B = analysis::ContactStatistics;
    std::vector<double> histogram(2 * B::bins);
    for (int w = 0; w < 2; ++w)
      std::copy(st.histogram[w].begin(), st.histogram[w].end(), histogram.begin() + w * B::bins);
    writer_->append_field("contact_statistics", step, t, {2, B::bins}, histogram,
                          {{"contacts", {2}, st.contacts},
                           {"beyond", {2}, st.beyond},
                           {"sliding_fraction", {2}, st.sliding},
                           {"coordination", {st.coordination.size()}, st.coordination}},
                          {{"bins", B::bin_centres()}, {"bin_width", {B::bin_width}}});
  }

  MpcdSimulation &sim_;
  std::unique_ptr<io::ObservablesWriter> writer_;
  analysis::ProfileAccumulator profiles_;
  SettlingSum settling_sum_;
  ColloidStatistics colloid_stats_;
  std::optional<AxialFields> axial_;
  double axial_seconds_ = 0.0;
  std::uint64_t axial_samples_ = 0;
  bool temperature_ = false, momentum_ = false, velocity_ = false, density_ = false,
       viscosity_ = false, energy_ = false, settling_ = false, positions_ = false,
       contacts_ = false;
};

} // namespace

// The checkpoint's data must fit the scene: the particle count the scene makes.
void check_fluid_count(const scene::Scene &scene, const io::CheckpointInfo &info,
                       const std::string &checkpoint) {
  std::array<int, 3> cells{1, 1, 1};
  for (int k = 0; k < scene.run.dimensions; ++k)
    cells[k] = static_cast<int>(std::lround(scene.domain.size[k]));
  const mpcd::Box box = mpcd::make_periodic_box(scene.run.dimensions, cells);
  // The space the colloids take holds no fluid: the count the run made (radii from the seed).
  const std::uint64_t count =
      scene.colloids
          ? fluid_count_with_colloids(*scene.colloids, box, scene.fluid.density, scene.run.seed)
          : mpcd::fluid_particle_count(box, scene.fluid.density);
  if (count != info.fluid_particles)
    throw input_error(checkpoint + ": holds " + std::to_string(info.fluid_particles) +
                      " fluid particles, the scene has " + std::to_string(count) +
                      "; allowed: a checkpoint of this scene");
}

namespace {

// The MPCD engine in the run loop (run/drive.hpp): the simulation's step, the observables, the
// trajectory and the checkpoints of fluid, colloids and contacts.
class MpcdEngine final : public run::Engine {
public:
  MpcdEngine(const scene::Scene &scene, MPI_Comm comm) : scene_(scene), comm_(comm) {
    // Refuse a decomposition the box cannot take before anything is written.
    check_ranks(scene, comm);
  }

  // The slabs' balance does not change results: a restart may change it.
  run::RunSpan span() const override {
    return {scene_.run.steps,
            "run.steps",
            {"domain.balance", "domain.balance_every", "domain.balance_threshold"}};
  }

  void start(run::Shell &shell) override {
    const scene::Scene &scene = scene_;
    const MPI_Comm comm = comm_;
    const bool restarting = shell.restarting();
    // A packing is made once, by the simulation below (it takes seconds to minutes).
    if (!restarting &&
        !(scene.colloids && scene.colloids->placement == scene::ColloidPlacement::packing))
      check_colloid_placement(scene);
    // The state, from the scene or the checkpoint (every rank agrees on a refusal) before
    // anything is written.
    MpcdSimulation &sim = sim_.emplace(scene, comm, !restarting);
    if (restarting) {
      const std::string &file = shell.restart_file();
      run::collectively(comm, [&] {
        const io::CheckpointInfo info = io::read_checkpoint_info(file, comm);
        check_fluid_count(scene, info, file);
        sim.restore(read_fluid(file, info, comm), info.step);
      });
      if (scene.colloids) {
        run::collectively(comm, [&] {
          colloids::Colloids all = read_colloids(file, *scene.colloids, scene.run.dimensions,
                                                 scene.fluid.density, scene.run.seed, comm);
          const bool springs = scene.colloids->contacts == scene::ColloidContacts::spring;
          colloids::ContactHistory contacts;
          contacts.dim = scene.run.dimensions;
          if (springs)
            contacts = read_contacts(file, scene.colloids->count, scene.run.dimensions,
                                     scene.walls.has_value(), comm);
          // Every rank holds all colloids and contacts: the same refusal everywhere.
          check_restored_colloids(all, contacts, scene,
                                  io::read_box_edges(file, "colloids", scene.run.dimensions, comm),
                                  shell.restart_info().step, file);
          sim.restore_colloids(std::move(all));
          if (springs)
            sim.restore_contacts(std::move(contacts));
        });
        // Every colloid (gathered from the owners) against this rank's fluid.
        check_fluid_outside_colloids(sim.fluid(), sim.gather_colloids(), sim.box(),
                                     scene.colloids->epsilon, scene.fluid.kT, file, comm);
      }
    }
    // Slabs balanced by work (by time too, before any is measured): from the initial state or the
    // checkpoint's colloids and contacts.
    if (scene.domain.balance != scene::Balance::none)
      sim.balance_work();
    // The colloid statistics, on a restart with the sums of the run chain so far.
    ColloidStatistics &colloid_stats = colloid_stats_.emplace(sim);
    if (restarting)
      run::collectively(comm, [&] { colloid_stats.restore(shell.restart_file(), comm); });
  }

  void open(run::Shell &shell, run::Log &log) override {
    const scene::Scene &scene = scene_;
    const MPI_Comm comm = comm_;
    MpcdSimulation &sim = *sim_;
    for (const auto &line : describe_scene(scene, comm))
      log.line(line);
    for (const auto &w : regime_warnings(scene))
      log.warn(w);
    if (shell.restarting())
      log.line("restarted from " + shell.restart_file() + " at step " + std::to_string(sim.step()));
    if (scene.domain.balance != scene::Balance::none && sim.slabs().ranks() > 1)
      log.line("slabs balanced by counted work: first columns " + slab_text(sim.slabs()) +
               (scene.domain.balance == scene::Balance::time
                    ? " (then by measured busy time every " +
                          std::to_string(scene.domain.balance_every) + " steps)"
                    : ""));
    if (const auto &p = sim.packing()) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "packing: %lld colloids at fraction %.4f, deepest overlap %.2e of the "
                    "smallest radius, %lld growth stages, %lld relaxation steps, %.2f s",
                    static_cast<long long>(scene.colloids->count), p->fraction, p->max_overlap,
                    static_cast<long long>(p->stages), static_cast<long long>(p->iterations),
                    p->seconds);
      log.line(line);
    }
    std::unique_ptr<io::ObservablesWriter> writer;
    if (shell.rank() == 0)
      writer =
          std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene.text);
    observer_.emplace(sim, std::move(writer), std::move(*colloid_stats_));
    // The trajectory and checkpoints hold every colloid: gathered from their owners when
    // written.
    if (scene.colloids) {
      colloids_ = &all_colloids_;
      all_colloids_ = sim.gather_colloids();
      // With axial_fields the frames carry each colloid's Voronoi fraction.
      if (observer_->axial())
        observer_->axial()->add_local_fraction(all_colloids_);
    }
    springs_ = scene.colloids && scene.colloids->contacts == scene::ColloidContacts::spring;
    if (scene.output.trajectory_every > 0) {
      const std::string file = shell.output_file("trajectory");
      trajectory_.emplace(file, scene.text, sim.box(), particle_count(scene),
                          static_cast<std::uint64_t>(scene.output.trajectory_subsample), comm,
                          colloids_, springs_);
      log.line("trajectory: " + std::to_string(trajectory_->tracked()) + " fluid particles" +
               (colloids_ ? " and " + std::to_string(colloids_->size()) + " colloids" : "") +
               (springs_ ? " with their contact network" : "") + " every " +
               std::to_string(scene.output.trajectory_every) + " steps to " + file +
               " (ParaView: trajectory" + shell.suffix() + ".xdmf)");
      if (!shell.restarting())
        write_frame();
    }
    invariants_.emplace(sim);
    n_particles_ = analysis::total_momentum(sim.fluid(), comm).count;
    talked_before_loop_ = parallel::message_seconds();
  }

  std::int64_t step() const override { return sim_->step(); }

  bool advance() override {
    sim_->advance();
    observer_->every_step();
    return true;
  }

  void observe() override {
    invariants_->check(*sim_);
    observer_->sample();
  }

  void write_frame() override {
    if (!trajectory_)
      return;
    if (colloids_) {
      all_colloids_ = sim_->gather_colloids();
      if (observer_->axial())
        observer_->axial()->add_local_fraction(all_colloids_);
    }
    std::optional<colloids::ContactNetwork> network;
    if (springs_) { // (every contact once: each is held by the rank of its owner colloid)
      all_contacts_ = sim_->gather_contacts();
      network = colloids::contact_network(all_colloids_, all_contacts_, sim_->box(),
                                          sim_->plan().no_slip_params.spring);
    }
    trajectory_->write_frame(sim_->step(), sim_->time(), sim_->fluid(), colloids_,
                             network ? &*network : nullptr);
  }

  // Checkpoints: every output.checkpoint_every steps, at the end, and on SIGTERM/SIGUSR1.
  std::string write_checkpoint(run::Shell &shell, const std::string &path) override {
    MpcdSimulation &sim = *sim_;
    Stopwatch watch;
    io::CheckpointInfo info = shell.checkpoint_info(sim.step(), sim.time());
    info.dimensions = sim.box().dim;
    info.box = sim.box().length;
    info.walls_y = sim.box().walls_y;
    std::vector<io::SpeciesFields> species{fluid_fields(sim.fluid())};
    colloids::Colloids none;
    colloids::ContactHistory no_contacts;
    if (colloids_) {
      all_colloids_ = sim.gather_colloids();
      species.push_back(colloid_fields(all_colloids_, none, comm_));
    }
    if (springs_) { // (none in contact: no species, as a checkpoint without a history)
      all_contacts_ = sim.gather_contacts();
      if (all_contacts_.size() > 0)
        species.push_back(contact_fields(all_contacts_, no_contacts, comm_));
    }
    const double bytes =
        io::write_checkpoint(path, info, species, comm_, observer_->checkpoint_arrays());
    const double s = watch.seconds();
    char text[200];
    std::snprintf(text, sizeof text, "%.1f MB of particles in %.3g s (%.1f MB/s)", bytes / 1e6, s,
                  s > 0 ? bytes / 1e6 / s : 0.0);
    return text;
  }

  run::Progress progress() const override {
    return {static_cast<double>(n_particles_), "particle-steps/s"};
  }

  // What the messages and the coupling cost, then the colloid statistics of the whole run.
  void finish(run::Log &log, const run::Loop &loop) override {
    const MpcdSimulation &sim = *sim_;
    const MPI_Comm comm = comm_;
    const double seconds = loop.seconds;
    const auto steps = static_cast<std::uint64_t>(loop.steps);
    // The largest of every rank's figure (on rank 0, which writes the log).
    const auto busiest = [&](double mine) {
      double most = 0.0;
      MPI_Reduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
      return most;
    };
    char text[200];
    // Bytes per step of a kind of message from the busiest rank, for scaling models of cluster
    // runs.
    const auto messages = [&](const char *what, std::uint64_t bytes, const char *which) {
      std::snprintf(text, sizeof text,
                    "%s messages: %.4g bytes per step from the busiest rank (%s)", what,
                    busiest(static_cast<double>(bytes)) / static_cast<double>(steps), which);
      log.line(text);
    };
    if (sim.slabs().ranks() > 1 && steps > 0 && seconds > 0.0) {
      messages("fluid", sim.fluid_bytes_sent(), "particles migrating to the slab of their cell");
      // Every exchange and collective of the steps, on the busiest and on the least busy rank.
      const double mine = parallel::message_seconds() - talked_before_loop_;
      const double most = busiest(mine), least = -busiest(-mine);
      std::snprintf(text, sizeof text,
                    "messages and waiting: %.4g-%.4g s of the loop (%.1f-%.1f %%) over the ranks "
                    "(every exchange of fluid and colloids and the steps' collectives)",
                    least, most, 100.0 * least / seconds, 100.0 * most / seconds);
      log.line(text);
    }
    if (scene_.colloids && steps > 0) { // the cost of colloids owned by slabs
      messages("colloid", sim.colloid_bytes_sent(), "ghosts, their forces, migration");
      if (const auto *ns = sim.no_slip(); ns && seconds > 0.0) { // the coupling's share
        const double most = busiest(ns->seconds());
        std::snprintf(text, sizeof text,
                      "no-slip coupling: %.4g s of the loop (%.1f %%) on the busiest rank "
                      "(colloid motion, bounce-back, ghost particles made and taken back)",
                      most, 100.0 * most / seconds);
        log.line(text);
        std::string stages = "no-slip coupling stages (s, busiest rank of each):";
        for (int k = 0; k < coupling::NoSlipCoupling::stage_count; ++k) {
          std::snprintf(text, sizeof text, "%s %s %.3g", k ? "," : "",
                        coupling::NoSlipCoupling::stage_name(k), busiest(ns->stage_seconds(k)));
          stages += text;
        }
        log.line(stages);
        if (sim.slabs().ranks() > 1) { // how much of it is messages and waiting
          const double talk = busiest(ns->message_seconds());
          std::snprintf(text, sizeof text,
                        "no-slip coupling messages: %.4g s of the loop (%.1f %%) on the busiest "
                        "rank (ghost colloids, impulse sums, migration; waiting for the other "
                        "ranks included)",
                        talk, 100.0 * talk / seconds);
          log.line(text);
        }
      }
      if (const auto *ns = sim.no_slip();
          ns && sim.scene().colloids->contacts == scene::ColloidContacts::hard) {
        // Rank 0's count: every collision of a colloid it owned, and those of its ghosts.
        std::snprintf(text, sizeof text,
                      "colloid contacts: %llu colloid-colloid and %llu colloid-wall collisions "
                      "resolved on rank 0 (ghosts included)",
                      static_cast<unsigned long long>(ns->contacts().pair_collisions),
                      static_cast<unsigned long long>(ns->contacts().wall_collisions));
        log.line(text);
      }
      if (const auto *ns = sim.no_slip(); ns && ns->springs()) {
        const double mine[2] = {static_cast<double>(ns->springs()->contact_updates()),
                                static_cast<double>(ns->springs()->sliding_updates())};
        double all[2] = {0.0, 0.0};
        MPI_Reduce(mine, all, 2, MPI_DOUBLE, MPI_SUM, 0, comm);
        std::snprintf(text, sizeof text,
                      "spring contacts: %.4g contact updates (sub-steps times contacts), %.1f %% "
                      "of them sliding",
                      all[0], all[0] > 0.0 ? 100.0 * all[1] / all[0] : 0.0);
        log.line(text);
      }
    }
    work_lines(log);
    if (const double s = busiest(observer_->axial_seconds_per_sample()); s > 0.0) {
      std::snprintf(text, sizeof text,
                    "axial_fields: %.3g ms per sample on the busiest rank (%lld colloids gathered, "
                    "their power diagram, the bins, the fluid sums)",
                    1e3 * s, static_cast<long long>(scene_.colloids->count));
      log.line(text);
    }
    if (const std::string cost = observer_->window_cost_line(); !cost.empty())
      log.line(cost);
    if (const std::string steady = observer_->steady_line(); !steady.empty())
      log.line(steady);
    observer_->finish();
  }

  run::LoopTime loop_time(const run::Loop &loop) const override {
    const auto steps = static_cast<std::uint64_t>(loop.steps);
    return {steps, "steps", std::to_string(n_particles_) + " particles",
            static_cast<double>(steps) * static_cast<double>(n_particles_), "particle-steps"};
  }

private:
  static std::string slab_text(const parallel::Slabs &slabs) {
    std::string s;
    for (int r = 0; r < slabs.ranks(); ++r)
      s += (r ? " " : "") + std::to_string(slabs.first_column_of(r));
    return s + " of " + std::to_string(slabs.columns());
  }

  // The counted work of each rank over the run (work_balance.hpp): its max/mean, the counts
  // summed over the ranks (for the weights), and the balance checks.
  void work_lines(run::Log &log) const {
    const MpcdSimulation &sim = *sim_;
    const WorkCounts &w = sim.work();
    const double mine[6] = {w.work(), w.fluid, w.colloids, w.contacts, w.bounces, w.ghosts};
    const int ranks = sim.slabs().ranks();
    std::vector<double> all(6 * static_cast<std::size_t>(ranks));
    MPI_Gather(mine, 6, MPI_DOUBLE, all.data(), 6, MPI_DOUBLE, 0, comm_);
    if (sim.slabs().rank() != 0 || sim.scene().run.steps == 0)
      return;
    std::vector<double> work(static_cast<std::size_t>(ranks));
    double sum[6] = {};
    for (int r = 0; r < ranks; ++r) {
      work[r] = all[6 * r];
      for (int k = 0; k < 6; ++k)
        sum[k] += all[6 * r + k];
    }
    char text[400];
    using W = WorkWeights;
    std::snprintf(text, sizeof text,
                  "counted work: max/mean %.4f over the ranks (fluid particle-steps, colloid "
                  "steps x %g, contact updates x %g, bounce-backs x %g, ghost particles x %g; "
                  "%s)",
                  imbalance(work), W::colloid, W::contact, W::bounce, W::ghost,
                  sim.scene().domain.balance == scene::Balance::work   ? "slabs balanced by work"
                  : sim.scene().domain.balance == scene::Balance::time ? "slabs balanced by time"
                                                                       : "equal slabs");
    std::string line = text;
    line += "; per rank:";
    for (int r = 0; r < ranks; ++r) {
      std::snprintf(text, sizeof text, " %.4g", work[r]);
      line += text;
    }
    log.line(line);
    std::snprintf(text, sizeof text,
                  "counted work totals: %.6g fluid particle-steps, %.6g colloid-steps, %.6g "
                  "contact updates, %.6g bounce-backs, %.6g ghost particles",
                  sum[1], sum[2], sum[3], sum[4], sum[5]);
    log.line(text);
    const auto &checks = sim.balance_checks();
    if (checks.empty())
      return;
    int moved = 0;
    for (const auto &c : checks)
      moved += c.moved ? 1 : 0;
    // Of the counted work, then of the busy time (the steps less their messages and waiting).
    for (const bool busy : {false, true}) {
      const auto value = [busy](const MpcdSimulation::BalanceCheck &c) {
        return busy ? c.busy_imbalance : c.imbalance;
      };
      const char *what = busy ? "busy time" : "counted work";
      double most = 0.0, mean = 0.0;
      for (const auto &c : checks) {
        most = std::max(most, value(c));
        mean += value(c) / static_cast<double>(checks.size());
      }
      std::snprintf(text, sizeof text,
                    "%s every %lld steps: max/mean first %.4f, mean %.4f, largest %.4f, last "
                    "%.4f; slabs moved %d times; now first columns %s",
                    what, static_cast<long long>(sim.scene().domain.balance_every),
                    value(checks.front()), mean, most, value(checks.back()), moved,
                    slab_text(sim.slabs()).c_str());
      log.line(text);
      line = std::string(what) + " max/mean per check (step: value, * slabs moved):";
      const std::size_t from = checks.size() > 40 ? checks.size() - 40 : 0;
      for (std::size_t i = from; i < checks.size(); ++i) {
        std::snprintf(text, sizeof text, " %lld: %.3f%s", static_cast<long long>(checks[i].step),
                      value(checks[i]), checks[i].moved ? "*" : "");
        line += text;
      }
      log.line(line);
    }
  }

  const scene::Scene &scene_;
  MPI_Comm comm_;
  std::optional<MpcdSimulation> sim_;
  double talked_before_loop_ = 0.0; // parallel::message_seconds() when the loop began
  std::optional<ColloidStatistics> colloid_stats_; // until open() hands it to the observer
  std::optional<Observer> observer_;
  std::optional<TrajectoryWriter> trajectory_;
  std::optional<InvariantCheck> invariants_;
  colloids::Colloids all_colloids_;
  const colloids::Colloids *colloids_ = nullptr; // &all_colloids_ with [colloids]
  bool springs_ = false;                         // spring contacts: their history is checkpointed
  colloids::ContactHistory all_contacts_;        // gathered in key order for checkpoints
  std::uint64_t n_particles_ = 0;
};

} // namespace

std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm) {
  check_colloid_placement(scene);
  std::vector<std::string> lines = describe_scene(scene, comm);
  for (const auto &w : regime_warnings(scene))
    lines.push_back("warning: " + w);
  return lines;
}

std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &,
                                         MPI_Comm comm) {
  return std::make_unique<MpcdEngine>(scene, comm);
}

} // namespace narrows::mpcd
