// The shifted collision grid and the binning kernel.
#include "narrows/mpcd/cell_grid.hpp"

#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::mpcd {

CellGrid::CellGrid(const Box &box) : dim(box.dim), cells(box.cells), sums(box.num_cells()) {
  if (dim == 2)
    cells[2] = 1;
}

std::array<double, 3> grid_shift(std::uint64_t seed, std::uint64_t step, int dim) {
  const auto r = rng::draw(seed, rng::Purpose::grid_shift, step, 0);
  std::array<double, 3> s{0.0, 0.0, 0.0};
  for (int k = 0; k < dim; ++k)
    s[k] = static_cast<double>(r[k]) * 0x1p-32 - 0.5;
  return s;
}

namespace {

// Cell coordinate of position x along an axis of n cells with grid shift s: floor(x - s),
// wrapped. x - s lies in (-1/2, L + 1/2), so one wrap each way suffices. (collision_at.cpp's
// in_cell uses the same floor(x - s), so cell and offset always agree.)
inline int cell_coordinate(double x, double s, int n) {
  int i = static_cast<int>(std::floor(x - s));
  i += (i < 0) ? n : 0;
  i -= (i >= n) ? n : 0;
  return i;
}

template <int D> void bin_kernel(Fluid &f, CellGrid &g) {
  std::fill(g.sums.begin(), g.sums.end(), CellSums{});
  const int nx = g.cells[0], ny = g.cells[1], nz = g.cells[2];
  const double sx = g.shift[0], sy = g.shift[1], sz = g.shift[2];
  const double *x = f.x[0].data(), *y = f.x[1].data(), *z = f.x[2].data();
  const double *vx = f.v[0].data(), *vy = f.v[1].data(), *vz = f.v[2].data();
  std::uint32_t *cell = f.cell.data();
  CellSums *sums = g.sums.data();
  const std::size_t n = f.size();
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t c = cell_coordinate(x[i], sx, nx) +
                    static_cast<std::size_t>(nx) * cell_coordinate(y[i], sy, ny);
    if constexpr (D == 3)
      c += static_cast<std::size_t>(nx) * ny * cell_coordinate(z[i], sz, nz);
    cell[i] = static_cast<std::uint32_t>(c);
    CellSums &s = sums[c];
    s.n += 1;
    s.p[0] += fixed::from_double(vx[i]);
    s.p[1] += fixed::from_double(vy[i]);
    if constexpr (D == 3)
      s.p[2] += fixed::from_double(vz[i]);
  }
}

} // namespace

void bin_particles(Fluid &fluid, CellGrid &grid) {
  if (grid.dim == 3)
    bin_kernel<3>(fluid, grid);
  else
    bin_kernel<2>(fluid, grid);
}

} // namespace narrows::mpcd
