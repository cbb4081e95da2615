// The MPCD fluid as a structure of arrays, and the periodic box it lives in.
#pragma once

#include "narrows/species/table.hpp"

#include <mpi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace narrows::mpcd {

// Box of whole collision cells (cell size a = 1), periodic along x and z; along y periodic too
// unless walls_y (planes at y = 0 and y = length[1]). z is unused in 2D.
struct Box {
  int dim = 2;
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> length{1.0, 1.0, 1.0};
  bool walls_y = false;
  std::size_t num_cells() const {
    return static_cast<std::size_t>(cells[0]) * cells[1] * (dim == 3 ? cells[2] : 1);
  }
};

// A periodic box of the given whole cells per axis (entries beyond dim are ignored).
Box make_periodic_box(int dim, std::array<int, 3> cells);

// Positions x[k], velocities v[k] (k < dim; the z arrays stay empty in 2D), 64-bit global
// ids, and the cell of each particle in the current shifted grid (recomputed every step,
// never trusted across steps). Every field is declared in table().
struct Fluid {
  int dim = 2;
  std::array<std::vector<double>, 3> x, v;
  std::vector<std::uint64_t> id;
  std::vector<std::uint32_t> cell;

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n); // every field of table()
};

// The fluid species' fields, one line each (the checkpoint's /particles/fluid/...).
species::Table table(Fluid &f);
// The same for reading only.
species::Table table(const Fluid &f);

// Number of particles of a box filled at a mean density: round(density * volume).
std::uint64_t fluid_particle_count(const Box &box, double density);

// Obstacles the fluid is kept out of (the colloids): `inside(p)` says whether p lies in one.
struct Exclusion {
  std::function<bool(const std::array<double, 3> &)> inside;
};

// Creates this rank's part of a fluid of `total` particles (ids 0..total-1) filling the box
// outside the obstacles: the particles whose cell column lies in [first_column, first_column +
// columns), so none has to move to another rank. Positions are uniform (redrawn inside an
// obstacle), velocities Maxwell-Boltzmann at kT (mass 1), both drawn from (seed, id), so the
// state does not depend on the number of ranks; then the mean velocity of all particles
// (summed exactly) is removed, so the total momentum is zero.
void init_fluid(Fluid &fluid, const Box &box, double kT, std::uint64_t seed, std::uint64_t total,
                int first_column, int columns, MPI_Comm comm, const Exclusion *exclusion = nullptr);

} // namespace narrows::mpcd
