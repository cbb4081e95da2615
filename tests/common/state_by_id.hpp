// Test helper for the bitwise comparisons of MPI runs: the whole fluid state as rows
// (x.., v..) indexed by particle id, gathered on rank 0 of comm.
#pragma once

#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdint>
#include <vector>

namespace narrows::testing {

// Exactly one rank holds each id, so summing with zeros elsewhere is exact; also checks that.
inline std::vector<double> state_by_id(const mpcd::Fluid &f, std::uint64_t total, MPI_Comm comm) {
  const int d = f.dim, row = 2 * d;
  std::vector<double> local(total * row, 0.0), global(total * row, 0.0);
  std::vector<int> seen_local(total, 0), seen(total, 0);
  for (std::size_t i = 0; i < f.size(); ++i) {
    for (int k = 0; k < d; ++k) {
      local[f.id[i] * row + k] = f.x[k][i];
      local[f.id[i] * row + d + k] = f.v[k][i];
    }
    seen_local[f.id[i]] += 1;
  }
  MPI_Reduce(local.data(), global.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_SUM, 0,
             comm);
  MPI_Reduce(seen_local.data(), seen.data(), static_cast<int>(total), MPI_INT, MPI_SUM, 0, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  for (std::uint64_t id = 0; id < total && rank == 0; ++id)
    EXPECT_EQ(seen[id], 1) << "id " << id << " held by " << seen[id] << " ranks";
  return global;
}

} // namespace narrows::testing
