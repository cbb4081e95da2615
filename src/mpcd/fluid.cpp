// Fluid storage and its initial state.
#include "narrows/mpcd/fluid.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace narrows::mpcd {

Box make_periodic_box(int dim, std::array<int, 3> cells) {
  Box b;
  b.dim = dim;
  for (int k = 0; k < 3; ++k) {
    b.cells[k] = k < dim ? cells[k] : 1;
    b.length[k] = b.cells[k];
  }
  return b;
}

void Fluid::resize(std::size_t n) {
  for (int k = 0; k < 3; ++k) {
    x[k].resize(k < dim ? n : 0);
    v[k].resize(k < dim ? n : 0);
  }
  id.resize(n);
  cell.resize(n);
}

std::uint64_t fluid_particle_count(const Box &box, double density) {
  double volume = 1.0;
  for (int k = 0; k < box.dim; ++k)
    volume *= box.length[k];
  return static_cast<std::uint64_t>(std::llround(density * volume));
}

namespace {

// Free space of a cell: the number of its 8 x 8 (3D: 4 x 4 x 4) sample points outside the
// obstacles.
std::uint64_t free_samples(const std::array<int, 3> &cell, int dim, const Exclusion &ex) {
  const int s = dim == 2 ? 8 : 4;
  std::uint64_t n = 0;
  for (int iz = 0; iz < (dim == 3 ? s : 1); ++iz)
    for (int iy = 0; iy < s; ++iy)
      for (int ix = 0; ix < s; ++ix) {
        const std::array<double, 3> p{cell[0] + (ix + 0.5) / s, cell[1] + (iy + 0.5) / s,
                                      dim == 3 ? cell[2] + (iz + 0.5) / s : 0.0};
        n += !ex.inside(p);
      }
  return n;
}

constexpr std::uint64_t all_samples = 64;
constexpr std::uint64_t max_attempts = 1000000;

} // namespace

void init_fluid(Fluid &fluid, const Box &box, double kT, std::uint64_t seed, std::uint64_t total,
                int first_column, int columns, MPI_Comm comm, const Exclusion *exclusion) {
  fluid.dim = box.dim;
  const int dim = box.dim, ny = box.cells[1], nz = dim == 3 ? box.cells[2] : 1;
  const std::size_t per_column = static_cast<std::size_t>(ny) * nz;
  const std::size_t local_cells = static_cast<std::size_t>(columns) * per_column;
  // This rank's cells in the global order, their coordinates, whether an obstacle may touch
  // them, and their free space.
  auto coordinates = [&](std::size_t c) {
    const std::size_t rest = c % per_column;
    return std::array<int, 3>{first_column + static_cast<int>(c / per_column),
                              static_cast<int>(rest % ny), static_cast<int>(rest / ny)};
  };
  auto box_index = [&](const std::array<int, 3> &q) {
    return (static_cast<std::size_t>(q[2]) * ny + q[1]) * box.cells[0] + q[0];
  };
  std::vector<std::uint64_t> weight(local_cells, all_samples);
  std::vector<std::uint8_t> touched(local_cells, 0);
  std::uint64_t local_weight = 0;
  for (std::size_t c = 0; c < local_cells; ++c) {
    if (exclusion) {
      const auto q = coordinates(c);
      touched[c] = exclusion->touches(box_index(q));
      if (touched[c])
        weight[c] = free_samples(q, dim, *exclusion);
    }
    local_weight += weight[c];
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::uint64_t before = 0, all = 0;
  MPI_Exscan(&local_weight, &before, 1, MPI_UINT64_T, MPI_SUM, comm);
  if (rank == 0)
    before = 0; // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&local_weight, &all, 1, MPI_UINT64_T, MPI_SUM, comm);
  const auto first_id = [&](std::uint64_t w) {
    return all ? static_cast<std::uint64_t>(static_cast<unsigned __int128>(total) * w / all) : 0;
  };
  const std::uint64_t id0 = first_id(before);
  fluid.resize(first_id(before + local_weight) - id0);

  const double sigma = std::sqrt(kT);
  std::array<std::int64_t, 3> local{0, 0, 0}, momentum{0, 0, 0};
  std::uint64_t w = before;
  for (std::size_t c = 0; c < local_cells; ++c) {
    const std::uint64_t lo = first_id(w), hi = first_id(w + weight[c]);
    w += weight[c];
    if (lo == hi)
      continue;
    const auto q = coordinates(c);
    for (std::uint64_t id = lo; id < hi; ++id) {
      const std::size_t i = id - id0;
      fluid.id[i] = id;
      std::array<double, 3> p{0.0, 0.0, 0.0};
      // Attempt a uses the steps 2a and 2a + 1 of the position stream; outside the cells an
      // obstacle may touch only the first attempt is made.
      for (std::uint64_t attempt = 0;; ++attempt) {
        const auto pos = rng::draw(seed, rng::Purpose::init_position, 2 * attempt, id);
        const auto pos2 = rng::draw(seed, rng::Purpose::init_position, 2 * attempt + 1, id);
        for (int k = 0; k < dim; ++k) {
          const double u =
              k < 2 ? rng::uniform53(pos[2 * k], pos[2 * k + 1]) : rng::uniform53(pos2[0], pos2[1]);
          // q + u can round up to q + 1 (the next column, perhaps another rank's): kept below.
          const double hi_edge = q[k] + 1.0;
          p[k] = std::min(q[k] + u, std::nextafter(hi_edge, 0.0));
        }
        if (!touched[c] || !exclusion->inside(p))
          break;
        if (attempt == max_attempts)
          throw invariant_error("initial fluid: no free place found in cell (" +
                                std::to_string(q[0]) + ", " + std::to_string(q[1]) + ", " +
                                std::to_string(q[2]) + ") in " + std::to_string(max_attempts) +
                                " attempts although a sample point of it is free");
      }
      const auto g = rng::gaussian4(rng::draw(seed, rng::Purpose::init_velocity, 0, id));
      for (int k = 0; k < dim; ++k) {
        fluid.x[k][i] = p[k];
        fluid.v[k][i] = sigma * g[k];
        local[k] += fixed::from_double(fluid.v[k][i]);
      }
    }
  }
  MPI_Allreduce(local.data(), momentum.data(), 3, MPI_INT64_T, MPI_SUM, comm);
  // Zero total momentum (seed 000 section 3.4.4): a net drift biases every flow measurement.
  for (int k = 0; k < dim; ++k) {
    const double mean = total ? fixed::to_double(momentum[k]) / static_cast<double>(total) : 0.0;
    for (auto &vk : fluid.v[k])
      vk -= mean;
  }
}

} // namespace narrows::mpcd
