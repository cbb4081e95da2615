// Observables of the MPCD fluid: temperature, total momentum, profiles across the channel.
// Reductions run over all ranks of the communicator.
#pragma once

#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::analysis {

// Total momentum as exact fixed-point sums (order- and rank-independent), particle count.
struct MomentumSum {
  std::array<std::int64_t, 3> fixed{0, 0, 0};
  std::uint64_t count = 0;
  std::array<double, 3> value() const;
};
MomentumSum total_momentum(const mpcd::Fluid &fluid, MPI_Comm comm);

// Kinetic temperature relative to the centre-of-mass velocity:
// kT = (sum v^2 - |P|^2/N) / (d (N - 1)), mass 1.
double temperature(const mpcd::Fluid &fluid, MPI_Comm comm);

// Velocity and density profiles across y in bins of one cell row, accumulated over the
// steps between two outputs and averaged.
class ProfileAccumulator {
public:
  ProfileAccumulator(const mpcd::Box &box);
  void add(const mpcd::Fluid &fluid);
  // Reduces over ranks; returns true on rank 0 with the averages filled in; then resets.
  bool finish(MPI_Comm comm, std::vector<double> &velocity, std::vector<double> &density);
  const std::vector<double> &bin_centres() const { return centres_; }
  double bin_width() const { return bin_width_; }
  int dim() const { return dim_; }

private:
  int dim_;
  double bin_width_, bin_volume_;
  std::vector<double> centres_;
  std::vector<double> sum_v_; // [bins][dim]
  std::vector<double> count_; // [bins]
  std::uint64_t samples_ = 0;
};

} // namespace narrows::analysis
