// The colloid statistics of an MPCD run (observables colloid_vacf, colloid_diffusion,
// colloid_msd, colloid_angular_vacf, density_kde, evolution, colloid_velocity_profile): samples
// all colloids (gathered in id order, so the same on any number of ranks) on their schedules,
// accumulates on rank 0 and writes the results of the whole run chain to observables.h5 when it
// ends; the sums travel in checkpoints. With output.kde_window > 0 the kernel profiles are
// averaged over consecutive windows of that many steps from colloids.statistics_from, each
// appended when it closes (the open window's sums, the first window's profile and the series
// of Delta travel in checkpoints too).
#pragma once

#include "narrows/analysis/colloid_time_correlations.hpp"
#include "narrows/analysis/kernel_density.hpp"
#include "narrows/analysis/kernel_windows.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace narrows::mpcd {

class ColloidStatistics {
public:
  // Nothing to do unless the scene has [colloids] and lists one of the observables; the run
  // starts at sim.step() and ends at run.steps.
  explicit ColloidStatistics(const MpcdSimulation &sim);
  bool active() const { return correlations_wanted_ || kde_wanted_ || velocity_wanted_; }
  // After every step (collective when a correlation sample is due).
  void after_step(const MpcdSimulation &sim);
  // At the observables cadence (collective): a density_kde (and colloid_velocity_profile)
  // sample; on rank 0 (writer non-null) the windows that close are appended.
  void on_observe(const MpcdSimulation &sim, io::ObservablesWriter *writer);
  // Rank 0 (the one with a writer): the results.
  void write(io::ObservablesWriter &writer, std::int64_t step, double time) const;
  // The accumulated sums for a checkpoint (rank 0's; empty on the others), and back from one
  // (collective): a restart continues the averages of the run chain. A checkpoint without
  // them (its run did not list the observable) starts new ones.
  std::vector<io::CheckpointArray> checkpoint_arrays() const;
  void restore(const std::string &checkpoint, MPI_Comm comm);
  // Rank 0: the steady-state line of evolution (empty without it).
  std::string steady_line() const;
  // Rank 0: what the windows cost this run (empty without windows).
  std::string window_cost_line() const;

private:
  // Appends the open window (ending at step `end`) and starts the next.
  void close_window(io::ObservablesWriter &writer);
  std::vector<double> window_state() const;

  bool correlations_wanted_ = false, kde_wanted_ = false, vacf_ = false, diffusion_ = false,
       msd_ = false, angular_ = false, accumulate_ = false, velocity_wanted_ = false,
       evolution_wanted_ = false;
  std::int64_t from_ = 0, every_ = 1;
  // Windows: their length (0: none), first step, the observables cadence, the open window.
  std::int64_t window_ = 0, window_start_ = 0, observe_every_ = 1, open_ = 0;
  double dt_ = 1.0;
  std::vector<double> per_kind_; // colloids per kind
  std::vector<std::size_t> kind_;
  std::array<double, 3> period_{0.0, 0.0, 0.0};
  std::optional<analysis::ColloidTimeCorrelations> correlations_;
  std::optional<analysis::KernelDensity> kde_;    // density_kde over the whole run
  std::optional<analysis::KernelWindow> windows_; // the open window's profiles
  std::vector<double> reference_;                 // evolution: the first window's F_k
  std::vector<double> delta_time_, delta_;        // evolution: Delta(t) of the closed windows
  // The windows' cost in this run (rank 0): samples, windows closed, their seconds.
  std::int64_t window_samples_ = 0, windows_closed_ = 0;
  double sample_seconds_ = 0.0, close_seconds_ = 0.0;
};

} // namespace narrows::mpcd
