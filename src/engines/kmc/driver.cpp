// Engine "kmc": replicas over ranks, reduction with error bars, the engine of the run loop,
// output, check/info, bench.
#include "narrows/engines/kmc/driver.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/kmc/lattice.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/models/three_state/preset.hpp"
#include "narrows/models/three_state/rates.hpp"
#include "narrows/models/three_state/shock.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/run/engine.hpp"
#include "narrows/run/shell.hpp"
#include "narrows/scene/parse.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <time.h>
#include <tuple>

namespace narrows::kmc {

using namespace narrows::three_state;

namespace {

std::string fmt(const char *format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// " 10->01 (w24) = 1;" (snprintf: GCC 12 warns falsely on chains of string +).
std::string item(const std::string &name, const std::string &label, double rate) {
  char buf[96];
  std::snprintf(buf, sizeof buf, " %s (%s) = %g;", name.c_str(), label.c_str(), rate);
  return buf;
}

// One replica's numbers as one array: current, density, mean, left, right, pair states,
// shock positions.
std::vector<double> pack(const ReplicaResult &r, const std::vector<double> &shock,
                         const std::vector<double> &charge) {
  std::vector<double> v;
  v.reserve(r.current.size() + r.density.size() + 3 + r.pair.size() + shock.size() + charge.size());
  v.insert(v.end(), r.current.begin(), r.current.end());
  v.insert(v.end(), r.density.begin(), r.density.end());
  v.push_back(r.mean_current);
  v.push_back(r.current_left);
  v.push_back(r.current_right);
  v.insert(v.end(), r.pair.begin(), r.pair.end());
  v.insert(v.end(), shock.begin(), shock.end());
  v.insert(v.end(), charge.begin(), charge.end());
  return v;
}

} // namespace

std::size_t replica_width(const scene::Kmc &model, ReplicaOptions options) {
  const std::size_t L = static_cast<std::size_t>(model.length);
  const std::size_t bonds = model.boundary == scene::KmcBoundary::periodic ? L : L - 1;
  const std::size_t samples = model.samples > 0 ? static_cast<std::size_t>(model.samples) + 1 : 0;
  return bonds + 3 * L + 3 + (options.pairs ? 9 * bonds : 0) + samples +
         (options.charge ? samples * L : 0);
}

ReplicaRounds::ReplicaRounds(const scene::Kmc &model, std::uint64_t seed, MPI_Comm comm,
                             ReplicaOptions options, ReplicaSums start)
    : model_(model), seed_(seed), comm_(comm), options_(options),
      width_(replica_width(model, options)), events0_(start.events), tries0_(start.tries),
      sums_(std::move(start)) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  const std::size_t samples = model.samples > 0 ? static_cast<std::size_t>(model.samples) + 1 : 0;
  for (std::size_t i = 0; i < samples; ++i)
    shock_time_.push_back(model.time * static_cast<double>(i) / static_cast<double>(samples - 1));
  // Rank 0 takes the replicas in replica order (Welford's running mean and squared
  // deviations), so the sums are done in one order whatever the number of ranks or restarts.
  if (rank_ == 0 && sums_.mean.empty()) {
    sums_.mean.assign(width_, 0.0);
    sums_.m2.assign(width_, 0.0);
  }
  buf_.resize(width_);
}

// One replica's numbers, or nothing if `stop` interrupted it.
std::vector<double> ReplicaRounds::run_one(std::int64_t r, const std::function<bool()> &stop) {
  const scene::Kmc &model = model_;
  LatticeOptions lo;
  lo.pair_histogram = options_.pairs;
  Lattice lattice(model, seed_, static_cast<std::uint64_t>(r), lo);
  if (!lattice.run_until(model.warmup, stop))
    return {};
  lattice.start_observing(model.time);
  std::vector<double> shock, charge;
  charge.reserve(options_.charge ? shock_time_.size() * static_cast<std::size_t>(model.length) : 0);
  for (std::size_t i = 0; i < shock_time_.size(); ++i) {
    if (!lattice.run_until(model.warmup + shock_time_[i], stop))
      return {};
    shock.push_back(
        static_cast<double>(shock_position(lattice.state(), model.initial, model.initial_right)));
    if (options_.charge)
      for (const auto n : lattice.state())
        charge.push_back(model.charge[n]);
  }
  if (!lattice.run_until(model.warmup + model.time, stop))
    return {};
  const ReplicaResult res = lattice.result();
  round_counts_[0] = res.events;
  round_counts_[1] = res.tries;
  return pack(res, shock, charge);
}

bool ReplicaRounds::round(const std::function<bool()> &stop) {
  const std::int64_t base = sums_.done;
  const std::int64_t r = base + rank_;
  round_counts_[0] = round_counts_[1] = 0;
  std::vector<double> mine;
  int dropped = 0;
  if (r < model_.replicas) {
    mine = run_one(r, stop);
    dropped = mine.empty() ? 1 : 0;
  }
  int any_dropped = 0;
  MPI_Allreduce(&dropped, &any_dropped, 1, MPI_INT, MPI_MAX, comm_);
  if (any_dropped)
    return false;
  if (rank_ != 0 && r < model_.replicas)
    MPI_Send(mine.data(), static_cast<int>(width_), MPI_DOUBLE, 0, 0, comm_);
  for (int q = 0; rank_ == 0 && q < ranks_ && base + q < model_.replicas; ++q) {
    if (q != 0)
      MPI_Recv(buf_.data(), static_cast<int>(width_), MPI_DOUBLE, q, 0, comm_, MPI_STATUS_IGNORE);
    const double *x = q == 0 ? mine.data() : buf_.data();
    const double n = static_cast<double>(base + q + 1);
    for (std::size_t i = 0; i < width_; ++i) {
      const double d = x[i] - sums_.mean[i];
      sums_.mean[i] += d / n;
      sums_.m2[i] += d * (x[i] - sums_.mean[i]);
    }
  }
  std::uint64_t counts[2] = {0, 0};
  MPI_Allreduce(round_counts_, counts, 2, MPI_UINT64_T, MPI_SUM, comm_);
  sums_.events += counts[0];
  sums_.tries += counts[1];
  sums_.done = std::min<std::int64_t>(base + ranks_, model_.replicas);
  return true;
}

Summary ReplicaRounds::summary() const {
  const scene::Kmc &model = model_;
  Summary s;
  s.replicas = model.replicas;
  s.shock_time = shock_time_;
  const std::size_t L = static_cast<std::size_t>(model.length);
  const std::size_t bonds = model.boundary == scene::KmcBoundary::periodic ? L : L - 1;
  const std::size_t samples = shock_time_.size();
  const std::size_t n_pair = options_.pairs ? 9 * bonds : 0;
  const std::size_t n_charge = options_.charge ? samples * L : 0;
  const std::size_t width = width_;
  double seconds = clock_.seconds();
  MPI_Allreduce(&seconds, &s.seconds, 1, MPI_DOUBLE, MPI_MAX, comm_);
  s.complete = finished();
  s.events = sums_.events - events0_;
  s.tries = sums_.tries - tries0_;
  s.sums = sums_;
  if (rank_ != 0 || !s.complete)
    return s;
  const std::vector<double> &mean = sums_.mean, &m2 = sums_.m2;
  const double R = static_cast<double>(model.replicas);
  std::vector<double> err(width, 0.0);
  if (model.replicas > 1)
    for (std::size_t i = 0; i < width; ++i)
      err[i] = std::sqrt(m2[i] / (R - 1.0) / R);
  const auto slice = [&](const std::vector<double> &v, std::size_t from, std::size_t n) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(from),
                               v.begin() + static_cast<std::ptrdiff_t>(from + n));
  };
  s.current = slice(mean, 0, bonds);
  s.current_error = slice(err, 0, bonds);
  s.density = slice(mean, bonds, 3 * L);
  s.density_error = slice(err, bonds, 3 * L);
  const std::size_t tail = bonds + 3 * L;
  s.mean_current = mean[tail];
  s.mean_current_error = err[tail];
  s.current_left = mean[tail + 1];
  s.current_left_error = err[tail + 1];
  s.current_right = mean[tail + 2];
  s.current_right_error = err[tail + 2];
  s.pair = slice(mean, tail + 3, n_pair);
  s.pair_error = slice(err, tail + 3, n_pair);
  const std::size_t sh = tail + 3 + n_pair;
  s.shock_mean = slice(mean, sh, samples);
  s.shock_mean_error = slice(err, sh, samples);
  for (std::size_t i = 0; i < samples; ++i) {
    const double var = model.replicas > 1 ? m2[sh + i] / (R - 1.0) : 0.0;
    s.shock_var.push_back(var);
    s.shock_var_error.push_back(model.replicas > 1 ? var * std::sqrt(2.0 / (R - 1.0)) : 0.0);
  }
  s.charge = slice(mean, sh + samples, n_charge);
  s.charge_error = slice(err, sh + samples, n_charge);
  return s;
}

Summary run_replicas(const scene::Kmc &model, std::uint64_t seed, MPI_Comm comm,
                     ReplicaOptions options, ReplicaSums start) {
  ReplicaRounds rounds(model, seed, comm, options, std::move(start));
  while (!rounds.finished())
    rounds.round();
  return rounds.summary();
}

std::vector<std::string> describe(const scene::Scene &scene) {
  const scene::Kmc &k = *scene.kmc;
  const bool open = k.boundary == scene::KmcBoundary::open;
  std::vector<std::string> out;
  out.push_back("engine kmc: three-state lattice gas, " + std::to_string(k.length) + " sites, " +
                (open ? "open boundaries" : "periodic"));
  std::string bulk = "bulk rates:";
  for (int from = 0; from < 9; ++from)
    for (int to = 0; to < 9; ++to)
      if (k.rates[from * 9 + to] > 0.0)
        bulk += item(pair_name(from, to), seed_label(from, to), k.rates[from * 9 + to]);
  out.push_back(bulk);
  if (open)
    for (int side = 0; side < 2; ++side) {
      std::string line = side == 0 ? "left (site 1) rates:" : "right (site L) rates:";
      const auto &t = side == 0 ? k.left : k.right;
      bool any = false;
      for (int from = 0; from < 3; ++from)
        for (int to = 0; to < 3; ++to)
          if (t[from * 3 + to] > 0.0) {
            line +=
                item(site_name(from, to), boundary_label(side == 0, from, to), t[from * 3 + to]);
            any = true;
          }
      out.push_back(any ? line : line + " none");
    }
  const auto probs = [](const std::array<double, 3> &p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
    return std::string(buf);
  };
  if (k.initial_kind == scene::KmcInitial::shock)
    out.push_back("initial: shock measure (eq 2.23) with P(0, 1, 2) = " + probs(k.initial) +
                  " on sites 1.." + std::to_string(k.shock_site) + " and " +
                  probs(k.initial_right) + " on the rest; shock position sampled " +
                  std::to_string(k.samples) +
                  " times (maximum-likelihood split between the two measures)");
  else
    out.push_back("initial: product measure P(0, 1, 2) = " + probs(k.initial));
  for (const auto &line : analyse(k).lines)
    out.push_back(line);
  out.push_back("time: warm-up " + fmt("%g", k.warmup) + ", observed " + fmt("%g", k.time) + "; " +
                std::to_string(k.replicas) + " replica(s), seeds from (run.seed = " +
                std::to_string(scene.run.seed) + ", replica)");
  out.push_back("current counts C(n) = (" + std::to_string(k.charge[0]) + ", " +
                std::to_string(k.charge[1]) + ", " + std::to_string(k.charge[2]) +
                ") moved left to right across each bond, per unit time");
  const double bytes = static_cast<double>(k.length) * (1.0 + 32.0 + 4.0 * 8.0);
  out.push_back("memory per replica: about " + fmt("%.3g", bytes / 1048576.0) + " MiB");
  out.push_back("dynamics: continuous time, uniformised: Poisson numbers of tries between fixed "
                "times, a try picks a bond or boundary site uniformly and accepts with rate / "
                "R_max; xoshiro256++ per replica");
  return out;
}

namespace {

ReplicaOptions replica_options(const scene::Scene &scene) {
  const auto &o = scene.output.observables;
  const auto wants = [&](const char *name) {
    return std::find(o.begin(), o.end(), name) != o.end();
  };
  ReplicaOptions options;
  options.pairs = wants("pair_correlation");
  options.charge = wants("charge_profile") && scene.kmc->samples > 0;
  return options;
}

// The running sums of a checkpoint hold the replica observables its scene asked for: a restart
// must ask for the same ones (the rest of the scene was compared by the run shell).
void check_replica_observables(const scene::Scene &given, const std::string &stored_text,
                               const std::string &checkpoint) {
  const auto stored = scene::parse_scene(stored_text, checkpoint + ":/parameters/scene");
  const ReplicaOptions og = replica_options(given), os = replica_options(stored);
  for (const auto &[name, a, b] : {std::tuple{"pair_correlation", og.pairs, os.pairs},
                                   std::tuple{"charge_profile", og.charge, os.charge}})
    if (a != b)
      throw input_error(given.file + ": output.observables " + (a ? "lists" : "lacks") + " \"" +
                        name + "\" but checkpoint " + checkpoint + (b ? " holds" : " lacks") +
                        " its running sums; allowed: the checkpoint's replica observables");
}

} // namespace

namespace {

// The kmc engine in the run loop: a step is one round of replicas (one per rank), the
// checkpoints hold the running sums over the finished replicas, the observables are written
// once every replica is done.
class KmcEngine final : public run::Engine {
public:
  KmcEngine(const scene::Scene &scene, MPI_Comm comm)
      : scene_(scene), comm_(comm), options_(replica_options(scene)),
        width_(replica_width(*scene.kmc, options_)) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
  }

  // The step of a kmc run is the number of finished replicas.
  run::RunSpan span() const override {
    return {scene_.kmc->replicas, "kmc.replicas", {"kmc.replicas"}};
  }

  void start(run::Shell &shell) override {
    shell_ = &shell;
    ReplicaSums start;
    if (shell.restarting()) {
      const std::string &restart_file = shell.restart_file();
      run::collectively(comm_, [&] {
        const io::CheckpointInfo &info = shell.restart_info();
        check_replica_observables(scene_, info.scene_text, restart_file);
        const auto counters = io::read_checkpoint_array(restart_file, "kmc/counters", 3, comm_);
        start.done = static_cast<std::int64_t>(counters[0]);
        start.events = static_cast<std::uint64_t>(counters[1]);
        start.tries = static_cast<std::uint64_t>(counters[2]);
        start.mean = io::read_checkpoint_array(restart_file, "kmc/mean", width_, comm_);
        start.m2 = io::read_checkpoint_array(restart_file, "kmc/m2", width_, comm_);
        if (rank_ != 0)
          start.mean.clear(), start.m2.clear();
        if (start.done != info.step)
          throw input_error(restart_file + ": /kmc/counters[0] = " + std::to_string(start.done) +
                            " but /parameters/step = " + std::to_string(info.step) +
                            "; allowed: the replicas done, the same in both");
      });
    }
    events0_ = start.events;
    rounds_.emplace(*scene_.kmc, scene_.run.seed, comm_, options_, std::move(start));
  }

  // A continuation's files carry the replicas done before it (log-0000000008.txt, ...).
  void open(run::Shell &shell, run::Log &log) override {
    const scene::Kmc &k = *scene_.kmc;
    const std::int64_t done = rounds_->sums().done;
    for (const auto &line : describe(scene_))
      log.line(line);
    for (const auto &w : analyse(k).warnings)
      log.warn(w);
    if (k.replicas == 1)
      log.warn("kmc.replicas = 1: no error bars (the *_error series are zero)");
    if ((k.replicas - done) % ranks_ != 0)
      log.warn(std::to_string(k.replicas - done) + " replicas on " + std::to_string(ranks_) +
               " ranks: some ranks idle at the end");
    if (shell.restarting())
      log.line("restarted from " + shell.restart_file() + " with " + std::to_string(done) + " of " +
               std::to_string(k.replicas) + " replicas done");
    // Rank 0 opens the output first, so a bad directory fails before the work.
    if (rank_ == 0)
      writer_ =
          std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene_.text);
  }

  std::int64_t step() const override { return rounds_->sums().done; }

  // On SIGTERM/SIGUSR1 the unfinished round of replicas is dropped (each rank asks about every
  // 2^20 tries).
  bool advance() override {
    return rounds_->round([this] { return shell_->stop_received() != 0; });
  }
  void observe() override {} // the observables are means over every replica: summary()

  // Rounds advance by the rank count: at least output.checkpoint_every replicas since the last.
  bool checkpoint_due(const run::Shell &shell, std::int64_t last) const override {
    return shell.checkpoint_due(step(), last);
  }

  // Checkpoints hold the running sums over the finished replicas: every
  // output.checkpoint_every replicas, at the end, and on SIGTERM/SIGUSR1.
  std::string write_checkpoint(run::Shell &shell, const std::string &path) override {
    const scene::Kmc &k = *scene_.kmc;
    const ReplicaSums &sums = rounds_->sums();
    io::CheckpointInfo info = shell.checkpoint_info(sums.done, k.time);
    info.dimensions = 1;
    info.box = {static_cast<double>(k.length), 1.0, 1.0};
    io::write_checkpoint(
        path, info, {}, comm_,
        {{"kmc/counters", rank_ == 0 ? std::vector<double>{static_cast<double>(sums.done),
                                                           static_cast<double>(sums.events),
                                                           static_cast<double>(sums.tries)}
                                     : std::vector<double>{}},
         {"kmc/mean", sums.mean},
         {"kmc/m2", sums.m2}});
    return std::to_string(sums.done) + " of " + std::to_string(k.replicas) + " replicas";
  }

  run::Progress progress() const override { return {0.0, nullptr, "replica"}; }

  std::string where() const override {
    return std::to_string(step()) + " of " + std::to_string(scene_.kmc->replicas) + " replicas";
  }

  // The means over every replica: observables and log lines.
  void summary(run::Log &log, const run::Loop &) override {
    const Summary s = rounds_->summary();
    write_results(s, log);
  }

  run::LoopTime loop_time(const run::Loop &) const override {
    const scene::Kmc &k = *scene_.kmc;
    const std::uint64_t events = rounds_->sums().events - events0_;
    return {events, "events",
            std::to_string(k.length) + " sites x " + std::to_string(k.replicas) + " replicas",
            static_cast<double>(events), "events"};
  }

private:
  void write_results(const Summary &s, run::Log &log);

  const scene::Scene &scene_;
  MPI_Comm comm_;
  ReplicaOptions options_;
  std::size_t width_;
  int rank_ = 0, ranks_ = 1;
  run::Shell *shell_ = nullptr;
  std::optional<ReplicaRounds> rounds_;
  std::uint64_t events0_ = 0;
  std::unique_ptr<io::ObservablesWriter> writer_;
};

void KmcEngine::write_results(const Summary &s, run::Log &log) {
  const scene::Scene &scene = scene_;
  const scene::Kmc &k = *scene.kmc;
  const int rank = rank_;
  const ReplicaOptions &options = options_;
  io::ObservablesWriter *writer = writer_.get();
  const auto wants = [&](const char *name) {
    const auto &o = scene.output.observables;
    return std::find(o.begin(), o.end(), name) != o.end();
  };

  if (rank == 0) {
    const double t = k.time;
    if (wants("current")) {
      std::vector<double> bins(s.current.size());
      for (std::size_t b = 0; b < bins.size(); ++b)
        bins[b] = static_cast<double>(b) + 1.5; // bond between sites b+1 and b+2 (1-based)
      writer->append_profile("current", 0, t, bins, s.current, 1);
      writer->append_profile("current_error", 0, t, bins, s.current_error, 1);
      writer->append_scalar("current_mean", 0, t, s.mean_current);
      writer->append_scalar("current_mean_error", 0, t, s.mean_current_error);
      if (k.boundary == scene::KmcBoundary::open) {
        const double jb[2] = {s.current_left, s.current_right};
        const double eb[2] = {s.current_left_error, s.current_right_error};
        writer->append_vector("current_boundary", 0, t, jb);
        writer->append_vector("current_boundary_error", 0, t, eb);
      }
    }
    if (wants("density_profile")) {
      std::vector<double> bins(static_cast<std::size_t>(k.length));
      for (std::size_t i = 0; i < bins.size(); ++i)
        bins[i] = static_cast<double>(i) + 1.0; // sites 1..L
      writer->append_profile("density_profile", 0, t, bins, s.density, 3);
      writer->append_profile("density_profile_error", 0, t, bins, s.density_error, 3);
    }
    if (options.pairs) {
      // Connected correlation P(n_k = a, n_(k+1) = b) - P(n_k = a) P(n_(k+1) = b) of the
      // replica means; its error is that of the pair probability (the product of two means
      // over all snapshots and replicas is far more precise).
      const std::size_t bonds = s.current.size(), L = static_cast<std::size_t>(k.length);
      std::vector<double> corr(9 * bonds), bins(bonds);
      for (std::size_t b = 0; b < bonds; ++b) {
        bins[b] = static_cast<double>(b) + 1.5;
        const std::size_t b2 = b + 1 == L ? 0 : b + 1;
        for (int c = 0; c < 9; ++c)
          corr[9 * b + c] =
              s.pair[9 * b + c] - s.density[3 * b + c / 3] * s.density[3 * b2 + c % 3];
      }
      writer->append_profile("pair_correlation", 0, t, bins, corr, 9);
      writer->append_profile("pair_correlation_error", 0, t, bins, s.pair_error, 9);
    }
    if (options.charge) {
      const std::size_t L = static_cast<std::size_t>(k.length);
      std::vector<double> bins(L);
      for (std::size_t i = 0; i < L; ++i)
        bins[i] = static_cast<double>(i) + 1.0;
      for (std::size_t i = 0; i < s.shock_time.size(); ++i) {
        const auto at = [&](const std::vector<double> &v) {
          return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(i * L),
                                     v.begin() + static_cast<std::ptrdiff_t>((i + 1) * L));
        };
        const auto step = static_cast<std::int64_t>(i);
        writer->append_profile("charge_profile", step, s.shock_time[i], bins, at(s.charge), 1);
        writer->append_profile("charge_profile_error", step, s.shock_time[i], bins,
                               at(s.charge_error), 1);
      }
    }
    if (k.preset != scene::KmcPreset::none) {
      // The preset's hydrodynamic flux j(density) (eq 2.48 with 2.59, or eq 2.126), for plots
      // and for tools/kmc_plot.py's solver of the hydrodynamic equation (eq 2.60).
      const bool f1 = k.preset == scene::KmcPreset::family1;
      std::vector<double> dens(401), flux(401);
      for (std::size_t i = 0; i < dens.size(); ++i) {
        const double u = static_cast<double>(i) / 400.0;
        dens[i] = f1 ? -1.0 + 2.0 * u : u;
        flux[i] = hydrodynamic_flux(k, dens[i]);
      }
      writer->append_profile("current_theory", 0, t, dens, flux, 1);
      const PresetReport rep = analyse(k);
      if (rep.shock) {
        const double theory[2] = {-rep.v_s, rep.d_s}; // velocity to the right, diffusion
        writer->append_vector("shock_theory", 0, t, theory);
      }
    }
    for (std::size_t i = 0; i < s.shock_time.size(); ++i) {
      const auto step = static_cast<std::int64_t>(i);
      writer->append_scalar("shock_position", step, s.shock_time[i], s.shock_mean[i]);
      writer->append_scalar("shock_position_error", step, s.shock_time[i], s.shock_mean_error[i]);
      writer->append_scalar("shock_position_variance", step, s.shock_time[i], s.shock_var[i]);
      writer->append_scalar("shock_position_variance_error", step, s.shock_time[i],
                            s.shock_var_error[i]);
    }
    writer->flush();
  }
  if (!s.shock_time.empty() && rank == 0) {
    // Drift to the right and diffusion from the first and the last sample.
    const std::size_t n = s.shock_time.size() - 1;
    const double T = s.shock_time[n];
    const double v = (s.shock_mean[n] - s.shock_mean[0]) / T;
    const double v_err = std::hypot(s.shock_mean_error[n], s.shock_mean_error[0]) / T;
    const double D = (s.shock_var[n] - s.shock_var[0]) / (2.0 * T);
    const double D_err = std::hypot(s.shock_var_error[n], s.shock_var_error[0]) / (2.0 * T);
    char line[256];
    std::snprintf(line, sizeof line,
                  "shock: velocity to the right %.5g +- %.2g, diffusion %.5g +- %.2g (first to "
                  "last sample)",
                  v, v_err, D, D_err);
    log.line(line);
    const PresetReport rep = analyse(k);
    if (rep.shock) {
      std::snprintf(line, sizeof line,
                    "shock theory: velocity to the right %.5g, diffusion %.5g (seed v_s = %.5g "
                    "to the left, D_s = %.5g)",
                    -rep.v_s, rep.d_s, rep.v_s, rep.d_s);
      log.line(line);
    }
  }
  char buf[256];
  std::snprintf(buf, sizeof buf, "mean current per bond J = %.6g +- %.2g (%lld replicas)",
                s.mean_current, s.mean_current_error, static_cast<long long>(k.replicas));
  log.line(buf);
  std::snprintf(buf, sizeof buf, "events %llu, tries per event %.3g",
                static_cast<unsigned long long>(s.events),
                s.events ? static_cast<double>(s.tries) / static_cast<double>(s.events) : 0.0);
  log.line(buf);
}

} // namespace

std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm) {
  std::vector<std::string> lines = describe(scene);
  for (const auto &w : analyse(*scene.kmc).warnings)
    lines.push_back("warning: " + w);
  return lines;
}

std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &,
                                         MPI_Comm comm) {
  return std::make_unique<KmcEngine>(scene, comm);
}

namespace {

// CPU time of the calling thread: on a shared machine it measures the engine, where wall time
// also counts the time the thread waited for a core.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

} // namespace

void run_bench(std::ostream &out, double sites, bool json) {
  struct Case {
    const char *name;
    scene::Kmc model;
  };
  const std::int64_t L = static_cast<std::int64_t>(sites);
  std::vector<Case> cases;
  {
    scene::Kmc m;
    m.length = L;
    m.boundary = scene::KmcBoundary::periodic;
    m.rates[pair_code(1, 0) * 9 + pair_code(0, 1)] = 1.0;
    m.initial = {0.5, 0.5, 0.0};
    cases.push_back({"tasep-periodic-half", m});
  }
  {
    // Family 1 (eq 2.5) with all ten rates 1, open, one third of each state.
    scene::Kmc m;
    m.length = L;
    const int pairs[5][2] = {{pair_code(1, 0), pair_code(0, 1)},
                             {pair_code(2, 0), pair_code(0, 2)},
                             {pair_code(1, 2), pair_code(2, 1)},
                             {pair_code(1, 1), pair_code(0, 2)},
                             {pair_code(2, 0), pair_code(1, 1)}};
    for (const auto &p : pairs) {
      m.rates[p[0] * 9 + p[1]] = 1.0;
      m.rates[p[1] * 9 + p[0]] = 1.0;
    }
    m.left[0 * 3 + 1] = 0.5;
    m.right[1 * 3 + 0] = 0.5;
    m.initial = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    cases.push_back({"family1-open-all-ones", m});
  }
  if (json)
    out << "{\"kmc\": [";
  bool first = true;
  for (auto &c : cases) {
    Lattice lattice(c.model, 1, 0);
    // Warm up for ~2 events per site, then time ~2e7 events with observables on.
    const double r0 = lattice.total_rate();
    lattice.run_until(2.0 * static_cast<double>(L) / r0);
    const double span = 2.0e7 / lattice.total_rate();
    lattice.start_observing(span);
    const double t0 = lattice.time();
    const std::uint64_t e0 = lattice.events(), tr0 = lattice.tries();
    Stopwatch clock;
    const double cpu0 = thread_cpu_seconds();
    lattice.run_until(t0 + span);
    const double sec = clock.seconds();
    const double cpu = thread_cpu_seconds() - cpu0;
    const double ev = static_cast<double>(lattice.events() - e0);
    const double tries = static_cast<double>(lattice.tries() - tr0);
    if (json) {
      out << (first ? "" : ", ") << "{\"case\": \"" << c.name << "\", \"sites\": " << L
          << ", \"events_per_s\": " << ev / sec << ", \"events_per_cpu_s\": " << ev / cpu
          << ", \"tries_per_event\": " << tries / ev << "}";
    } else {
      char buf[240];
      std::snprintf(buf, sizeof buf,
                    "kmc %-24s L = %.3g: %.3g events/s on one core (%.3g tries/event, %.3g s; "
                    "%.3g per CPU second)",
                    c.name, sites, ev / sec, tries / ev, sec, ev / cpu);
      out << buf << '\n';
    }
    first = false;
  }
  if (json)
    out << "]}\n";
}

} // namespace narrows::kmc
