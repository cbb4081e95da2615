// The shifted collision grid: per-cell particle counts and fixed-point momentum sums, and the
// binning kernel that fills them.
#pragma once

#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace narrows::mpcd {

// Counts and fixed-point sums of one cell (order-independent, see core/fixed_point.hpp).
struct CellSums {
  std::array<std::int64_t, 3> p{0, 0, 0}; // momentum (mass 1)
  std::uint32_t n = 0;
};

// A cell cut by a wall, filled to the mean density by virtual particles
// (Tabatabaei (2008) eq 3.14): only their number and the sums of their velocities and of their
// MPC-AT noise are needed.
struct VirtualCell {
  std::uint32_t cell = 0; // local cell index
  double count = 0.0;     // number of virtual particles, density - real count
  std::array<double, 3> momentum{0.0, 0.0, 0.0}; // sum of their velocities (wall at rest)
  std::array<double, 3> noise{0.0, 0.0, 0.0};    // sum of their MPC-AT Gaussian velocities
};

// Particles of one cell known only by their sums (the ghost particles of a no-slip colloid in
// a cell it cuts): positions r as offsets from the cell's corner (the collision rules' in_cell),
// velocities v, and the Gaussian velocities xi the MPC-AT rules give them. Whoever lists a
// group also adds its count and its summed velocity to the cell's sums (as binning would).
// Tensors are full 3x3, [3 a + b] = sum r_a r_b or sum r_a v_b (zero rows and columns in 2D).
struct ParticleGroup {
  std::uint32_t cell = 0; // local cell index
  std::uint32_t n = 0;    // number of particles
  std::array<double, 3> r{0.0, 0.0, 0.0};
  std::array<double, 9> rr{};
  std::array<double, 3> v{0.0, 0.0, 0.0};
  std::array<double, 9> rv{};
  std::array<double, 3> xi{0.0, 0.0, 0.0};
  std::array<double, 9> rxi{};
};

// What a collision did to a group: the sums of v' - v and of r_a (v'_b - v_b); and
// `response`, how the new velocity v' of each other particle of the cell changes with the
// cell's mean velocity u before the collision, [3 b + c] = d v'_b / d u_c (SRD: 1 - R; the
// MPC-AT rules: 1); and for MPC-AT+a the cell's centre rc (from the corner) and inverse moment
// of inertia `spin` (3 x 3; 2D: [8] = 1/I): the rigid rotation dw = spin dL that a change dL of
// the cell's angular momentum about rc adds, v' += dw x (r - rc). For the implicit exchange of
// no-slip colloids (coupling/no_slip.hpp).
struct GroupChange {
  std::array<double, 3> v{0.0, 0.0, 0.0};
  std::array<double, 9> rv{};
  std::array<double, 9> response{};
  std::array<double, 3> rc{0.0, 0.0, 0.0};
  std::array<double, 9> spin{};
};

// The cells one rank owns: its slab of x columns [first_column, first_column + cells[0]) of
// the global grid (global_columns wide, periodic), and all of y (and z).
// With walls at y = 0 and y = L_y the y axis is not periodic: the grid has L_y + 1 rows, the
// y shift lies in [0, 1), row j covers [j - 1 + s, j + s), and rows 0 and L_y are cut by the
// walls.
struct CellGrid {
  int dim = 2;
  std::array<int, 3> cells{1, 1, 1}; // local: x columns of the slab, y rows, z
  int first_column = 0;
  int global_columns = 1;
  bool walls_y = false;
  std::array<double, 3> shift{0.0, 0.0, 0.0}; // grid origin offset, each in [-1/2, 1/2)
  std::vector<CellSums> sums;
  std::vector<VirtualCell> virtual_cells; // filled by walls::add_virtual_particles
  std::vector<ParticleGroup> groups;      // filled by colloids' add_ghost_particles

  // The whole box (one rank), or the slab [first_column, first_column + columns).
  explicit CellGrid(const Box &box, int first_column = 0, int columns = -1);
  CellGrid() = default;
  std::size_t size() const { return sums.size(); }
  // Sets the shift of a step (from grid_shift); with walls the y shift moves to [0, 1).
  void set_shift(const std::array<double, 3> &s) {
    shift = s;
    if (walls_y)
      shift[1] += 0.5;
  }
  // Global index of local cell c: the key of per-cell random draws, the same whichever rank
  // owns the cell, so results do not depend on the number of ranks.
  std::uint64_t global_id(std::size_t c) const {
    const std::size_t nx = static_cast<std::size_t>(cells[0]);
    return (c % nx + static_cast<std::size_t>(first_column)) +
           static_cast<std::uint64_t>(global_columns) * (c / nx);
  }
};

// Offset of a particle at x from the corner of its shifted cell (shift s), in [0, 1): the same
// floor(x - s) as cell_coordinate, so cell and offset always agree.
inline double in_cell_offset(double x, double s) {
  const double t = x - s;
  return t - std::floor(t);
}

// Shift of the collision grid at a step, uniform in [-1/2, 1/2) per axis; the same on every
// rank without a message because it depends only on (seed, step).
std::array<double, 3> grid_shift(std::uint64_t seed, std::uint64_t step, int dim);

// Cell coordinate of position x along an axis of n cells with grid shift s: floor(x - s),
// wrapped. x lies in [0, L) and s in [-1/2, 1/2), so x - s lies in (-1/2, L + 1/2) and one
// wrap each way suffices. (in_cell_offset uses the same floor(x - s), so cell and offset always
// agree.)
// A coordinate no cell can hold (not finite, or beyond the box it should have been wrapped
// into): a broken invariant naming the particle (species may be null), never an index.
[[noreturn]] void no_cell(double x, int axis, double length, const char *species, std::uint64_t id);

inline int cell_coordinate(double x, double s, int n, int axis = 0, const char *species = nullptr,
                           std::uint64_t id = 0) {
  const double f = std::floor(x - s);
  if (!(f >= -n && f < 2.0 * n)) [[unlikely]]
    no_cell(x, axis, n, species, id);
  int i = static_cast<int>(f);
  i += (i < 0) ? n : 0;
  i -= (i >= n) ? n : 0;
  return i;
}

// Row of position y in a grid with walls (y in [0, L_y], shift s in [0, 1)): floor(y - s) + 1,
// clamped so that a particle exactly on the upper wall with s = 0 stays in the last row.
inline int wall_row(double y, double s, int rows, const char *species = nullptr,
                    std::uint64_t id = 0) {
  const double f = std::floor(y - s);
  if (!(f >= -rows && f < 2.0 * rows)) [[unlikely]]
    no_cell(y, 1, rows - 1, species, id);
  int j = static_cast<int>(f) + 1;
  j = j < 0 ? 0 : j;
  return j < rows ? j : rows - 1;
}

// Cell along one axis of a cell list of n cells of width 1/inv over [0, n/inv]: clamped into
// [0, n) (a position on the upper edge, or rounded just below zero, stays in the edge cell);
// a coordinate more than a box length outside, or not finite, is refused by no_cell.
inline int clamped_cell(double x, double inv, int n, const char *species, std::uint64_t id,
                        int axis) {
  const double f = x * inv;
  if (!(f > -n && f < 2.0 * n)) [[unlikely]]
    no_cell(x, axis, n / inv, species, id);
  const int i = static_cast<int>(f);
  return i < 0 ? 0 : (i < n ? i : n - 1);
}

// Particles found outside this rank's slab while binning: index and global x column.
struct Strays {
  std::vector<std::size_t> index;
  std::vector<int> column;
  void clear() {
    index.clear();
    column.clear();
  }
};

// Assigns each particle its cell of the shifted grid and fills the cell sums (from zero).
// A particle outside this grid's slab is an invariant error, unless `strays` is given: then
// it is listed there (for migration) and left out of the sums.
void bin_particles(Fluid &fluid, CellGrid &grid, Strays *strays = nullptr);

// Adds particles [first, size) to the cell sums (e.g. arrivals after migration); each must
// lie in the slab.
void bin_more_particles(Fluid &fluid, CellGrid &grid, std::size_t first);

} // namespace narrows::mpcd
