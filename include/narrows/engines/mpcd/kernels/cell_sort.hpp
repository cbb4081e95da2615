// Counting sort of the fluid by cell, for memory locality of the binning and collision loops.
#pragma once

#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <cstdint>
#include <vector>

namespace narrows::mpcd {

// Buffers the sort swaps arrays with, kept between sorts so the step loop does not allocate.
struct SortScratch {
  std::vector<double> real;
  std::vector<std::uint64_t> ids;
  std::vector<std::uint32_t> cells, dest, start;
};

// Reorders every fluid array so particles of one cell are contiguous, in cell order of the
// last binning (fluid.cell must be current). Stable, O(N + cells).
void sort_by_cell(Fluid &fluid, const CellGrid &grid, SortScratch &scratch);

} // namespace narrows::mpcd
