// Engine "kmc": replicas spread over MPI ranks and reduced with error bars, the check/info text
// and the engine of `narrows run` for kmc scenes, and the kmc benchmark.
#pragma once

#include "narrows/core/timer.hpp"
#include "narrows/run/engine.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace narrows::kmc {

// Where a run of replicas stands: replicas [0, done) are in the running sums, which is all a
// checkpoint of the kmc engine has to hold (replicas are pure functions of (seed, replica)).
struct ReplicaSums {
  std::int64_t done = 0;
  std::vector<double> mean, m2; // rank 0: Welford mean and sum of squared deviations [width]
  std::uint64_t events = 0, tries = 0;
};

// Means over replicas and standard errors of the mean (sample standard deviation / sqrt(R);
// zero when R = 1). Filled on rank 0 only, except events, tries and seconds (every rank).
struct Summary {
  std::int64_t replicas = 0;
  std::vector<double> current, current_error;            // per bond: [L-1] open, [L] periodic
  std::vector<double> density, density_error;            // [L][3]
  double mean_current = 0.0, mean_current_error = 0.0;   // averaged over bonds
  double current_left = 0.0, current_left_error = 0.0;   // reservoir -> site 1
  double current_right = 0.0, current_right_error = 0.0; // site L -> reservoir
  std::vector<double> pair, pair_error;                  // [bonds][9] P(n_k n_(k+1) = code)
  // Shock position (kmc.samples > 0) at times shock_time (from the start of the observation):
  // mean and its error, variance over replicas and its error (Gaussian: var sqrt(2/(R-1))).
  std::vector<double> shock_time, shock_mean, shock_mean_error, shock_var, shock_var_error;
  // Charge C(n_k) of every site at those times (if asked for): [samples][L], mean and error.
  std::vector<double> charge, charge_error;
  std::uint64_t events = 0, tries = 0; // summed over ranks, this call's replicas only
  double seconds = 0.0;                // wall time of this call, slowest rank
  bool complete = true;                // false: stopped early, only `sums` is meaningful
  ReplicaSums sums;                    // where the run stands (for its checkpoint)
};

struct ReplicaOptions {
  bool pairs = false;  // pair histograms of every bond
  bool charge = false; // the charge of every site at the sample times
};

// The numbers one replica contributes (current, density, boundary currents, pairs, shock
// positions, charges), the width of the running sums.
std::size_t replica_width(const scene::Kmc &model, ReplicaOptions options);

// Replicas run in rounds: round k runs replica done + q on rank q (done: the replicas finished
// before it); rank 0 reduces in replica order, so the numbers are bitwise the same on any number
// of ranks, and the same whether or not the run was resumed from `start` (the sums of an earlier
// run with the same model and seed). The kmc engine advances one round per step of the run
// loop (run/drive.hpp).
class ReplicaRounds {
public:
  ReplicaRounds(const scene::Kmc &model, std::uint64_t seed, MPI_Comm comm,
                ReplicaOptions options = {}, ReplicaSums start = {});
  // Collective: one round. `stop` (this rank only) is asked about every 2^20 tries inside a
  // replica; if it answers true on any rank, the unfinished round is dropped: false on every
  // rank, the sums as they were.
  bool round(const std::function<bool()> &stop = nullptr);
  bool finished() const { return sums_.done >= model_.replicas; }
  // Where the run stands (for its checkpoint): complete on rank 0.
  const ReplicaSums &sums() const { return sums_; }
  // Collective: the means and errors (rank 0, if finished), the events and tries of this
  // object's rounds, and its wall time.
  Summary summary() const;

private:
  std::vector<double> run_one(std::int64_t replica, const std::function<bool()> &stop);

  const scene::Kmc &model_;
  std::uint64_t seed_;
  MPI_Comm comm_;
  ReplicaOptions options_;
  int rank_ = 0, ranks_ = 1;
  std::size_t width_;
  std::vector<double> shock_time_;
  std::uint64_t events0_, tries0_;
  ReplicaSums sums_;
  std::vector<double> buf_;
  std::uint64_t round_counts_[2] = {0, 0}; // events, tries of this rank in this round
  Stopwatch clock_;
};

// Every round of replicas from `start` to model.replicas (ReplicaRounds).
Summary run_replicas(const scene::Kmc &model, std::uint64_t seed, MPI_Comm comm,
                     ReplicaOptions options = {}, ReplicaSums start = {});

// What `check` / `info` print for a kmc scene.
std::vector<std::string> describe(const scene::Scene &scene);

// `narrows check|info`: describe()'s lines and the preset's warnings ("warning: ...").
std::vector<std::string> check_lines(const scene::Scene &scene, MPI_Comm comm);

// `narrows run`: the engine of a kmc scene for run::drive: DIR/log.txt, DIR/observables.h5,
// the "Loop time" line, checkpoints (the running sums over finished replicas); a restart
// continues such a run, bitwise as if never interrupted.
std::unique_ptr<run::Engine> make_engine(const scene::Scene &scene, const run::Options &options,
                                         MPI_Comm comm);

// `narrows bench --kmc`: events per second on one core for L = sites.
void run_bench(std::ostream &out, double sites, bool json);

} // namespace narrows::kmc
