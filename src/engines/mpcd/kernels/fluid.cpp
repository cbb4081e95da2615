// Fluid storage and its initial state.
#include "narrows/engines/mpcd/kernels/fluid.hpp"

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

species::Table table(Fluid &f) {
  using namespace species;
  // The cell index travels with a particle, so a row moved within a rank keeps its binning
  // (arrivals are binned again); it is recomputed every step, so never stored.
  constexpr unsigned stored = migrates | checkpoint;
  Table t("fluid", f.dim);
  t.vector("position", f.x, stored | trajectory)
      .vector("velocity", f.v, stored | trajectory)
      .scalar("id", f.id, stored)
      .scalar("cell", f.cell, migrates);
  return t;
}

species::Table table(const Fluid &f) {
  species::Table t = table(const_cast<Fluid &>(f));
  t.read_only();
  return t;
}

void Fluid::resize(std::size_t n) { table(*this).resize(n); }

std::uint64_t fluid_particle_count(const Box &box, double density) {
  double volume = 1.0;
  for (int k = 0; k < box.dim; ++k)
    volume *= box.length[k];
  return static_cast<std::uint64_t>(std::llround(density * volume));
}

namespace {

constexpr std::uint64_t max_attempts = 1000000;

} // namespace

void init_fluid(Fluid &fluid, const Box &box, double kT, std::uint64_t seed, std::uint64_t total,
                int first_column, int columns, MPI_Comm comm, const Exclusion *exclusion) {
  fluid.dim = box.dim;
  fluid.resize(0);
  const int dim = box.dim;
  const double sigma = std::sqrt(kT);
  std::array<std::int64_t, 3> local{0, 0, 0}, momentum{0, 0, 0};
  // Every rank draws the position of every id (a pure function of seed and id, so the state is
  // that of one rank) and keeps those in its own columns: ideal-gas (Poisson) cell occupancy
  // as on one rank, nothing to migrate, no message. The price is O(total) draws on each rank
  // at the start (about 20 ns each), not memory.
  for (std::uint64_t id = 0; id < total; ++id) {
    std::array<double, 3> p{0.0, 0.0, 0.0};
    // Attempt a uses the steps 2a and 2a + 1 of the position stream; without exclusions only
    // the first attempt is made.
    for (std::uint64_t attempt = 0;; ++attempt) {
      const auto pos = rng::draw(seed, rng::Purpose::init_position, 2 * attempt, id);
      const auto pos2 = rng::draw(seed, rng::Purpose::init_position, 2 * attempt + 1, id);
      for (int k = 0; k < dim; ++k) {
        const double u =
            k < 2 ? rng::uniform53(pos[2 * k], pos[2 * k + 1]) : rng::uniform53(pos2[0], pos2[1]);
        p[k] = u * box.length[k];
      }
      if (!exclusion || !exclusion->inside(p))
        break;
      if (attempt == max_attempts)
        throw invariant_error("initial fluid: no free place found for particle " +
                              std::to_string(id) + " in " + std::to_string(max_attempts) +
                              " attempts");
    }
    // The column as the cell grid bins it (one cell per unit length along x).
    const int column =
        std::min(box.cells[0] - 1, static_cast<int>(p[0] * box.cells[0] / box.length[0]));
    if (column < first_column || column >= first_column + columns)
      continue;
    const auto g = rng::gaussian4(rng::draw(seed, rng::Purpose::init_velocity, 0, id));
    fluid.id.push_back(id);
    fluid.cell.push_back(0);
    for (int k = 0; k < dim; ++k) {
      fluid.x[k].push_back(p[k]);
      fluid.v[k].push_back(sigma * g[k]);
      local[k] += fixed::from_double(fluid.v[k].back());
    }
  }
  fluid.resize(fluid.id.size()); // (fields not drawn here: their fill)
  MPI_Allreduce(local.data(), momentum.data(), 3, MPI_INT64_T, MPI_SUM, comm);
  // Zero total momentum (Tabatabaei (2008) section 3.4.4): a net drift biases every
  // flow measurement.
  for (int k = 0; k < dim; ++k) {
    const double mean = total ? fixed::to_double(momentum[k]) / static_cast<double>(total) : 0.0;
    for (auto &vk : fluid.v[k])
      vk -= mean;
  }
}

} // namespace narrows::mpcd
