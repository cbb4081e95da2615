// The MPCD fluid as a structure of arrays, and the periodic box it lives in.
#pragma once

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
// never trusted across steps).
struct Fluid {
  int dim = 2;
  std::array<std::vector<double>, 3> x, v;
  std::vector<std::uint64_t> id;
  std::vector<std::uint32_t> cell;

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n);
};

// Number of particles of a box filled at a mean density: round(density * volume).
std::uint64_t fluid_particle_count(const Box &box, double density);

// Creates the particles with ids [first_id, first_id + count) of a fluid filling the box:
// positions uniform, velocities Maxwell-Boltzmann at kT (mass 1), then the mean velocity of
// all `total` particles (summed exactly over the ranks of comm) removed, so the total momentum
// is zero. Each particle's state depends only on (seed, id), not on the rank that makes it.
// Positions for which `excluded` (if given) is true are drawn again (the space colloids take).
using Excluded = std::function<bool(const std::array<double, 3> &)>;
void init_fluid(Fluid &fluid, const Box &box, double kT, std::uint64_t seed, std::uint64_t first_id,
                std::uint64_t count, std::uint64_t total, MPI_Comm comm,
                const Excluded &excluded = nullptr);

} // namespace narrows::mpcd
