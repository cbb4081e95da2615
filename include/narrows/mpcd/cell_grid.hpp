// The shifted collision grid: per-cell particle counts and fixed-point momentum sums, and the
// binning kernel that fills them.
#pragma once

#include "narrows/mpcd/fluid.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::mpcd {

// Counts and fixed-point sums of one cell (order-independent, see core/fixed_point.hpp).
struct CellSums {
  std::array<std::int64_t, 3> p{0, 0, 0}; // momentum (mass 1)
  std::uint32_t n = 0;
};

struct CellGrid {
  int dim = 2;
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> shift{0.0, 0.0, 0.0}; // grid origin offset, each in [-1/2, 1/2)
  std::vector<CellSums> sums;

  explicit CellGrid(const Box &box);
  CellGrid() = default;
  std::size_t size() const { return sums.size(); }
  // Global index of local cell c: the key of per-cell random draws. (One rank owns the whole
  // grid for now; slabs will add their column offset here.)
  std::uint64_t global_id(std::size_t c) const { return c; }
};

// Shift of the collision grid at a step, uniform in [-1/2, 1/2) per axis; the same on every
// rank without a message because it depends only on (seed, step).
std::array<double, 3> grid_shift(std::uint64_t seed, std::uint64_t step, int dim);

// Assigns each particle its cell of the shifted grid and fills the cell sums.
void bin_particles(Fluid &fluid, CellGrid &grid);

} // namespace narrows::mpcd
