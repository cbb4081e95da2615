// The colloid statistics of an MPCD run (observables colloid_vacf, colloid_diffusion,
// colloid_msd, colloid_angular_vacf, density_kde): samples all colloids (gathered in id order,
// so the same on any number of ranks) on their schedules, accumulates on rank 0 and writes the
// results of the whole run chain to observables.h5 when it ends; the sums travel in checkpoints.
#pragma once

#include "narrows/analysis/colloid_time_correlations.hpp"
#include "narrows/analysis/kernel_density.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"

#include <cstdint>
#include <optional>

namespace narrows::mpcd {

class ColloidStatistics {
public:
  // Nothing to do unless the scene has [colloids] and lists one of the observables; the run
  // starts at sim.step() and ends at run.steps.
  explicit ColloidStatistics(const MpcdSimulation &sim);
  bool active() const { return correlations_wanted_ || kde_wanted_; }
  // After every step (collective when a correlation sample is due).
  void after_step(const MpcdSimulation &sim);
  // At the observables cadence (collective): a density_kde sample.
  void on_observe(const MpcdSimulation &sim);
  // Rank 0 (the one with a writer): the results.
  void write(io::ObservablesWriter &writer, std::int64_t step, double time) const;
  // The accumulated sums for a checkpoint (rank 0's; empty on the others), and back from one
  // (collective): a restart continues the averages of the run chain. A checkpoint without
  // them (its run did not list the observable) starts new ones.
  std::vector<io::CheckpointArray> checkpoint_arrays() const;
  void restore(const std::string &checkpoint, MPI_Comm comm);

private:
  bool correlations_wanted_ = false, kde_wanted_ = false, vacf_ = false, diffusion_ = false,
       msd_ = false, angular_ = false, accumulate_ = false;
  std::int64_t from_ = 0, every_ = 1;
  std::vector<std::size_t> kind_;
  std::array<double, 3> period_{0.0, 0.0, 0.0};
  std::optional<analysis::ColloidTimeCorrelations> correlations_;
  std::optional<analysis::KernelDensity> kde_;
};

} // namespace narrows::mpcd
