// The colloid forces as the sum of their terms, in fixed point.
#include "narrows/colloids/forces.hpp"
#include "narrows/colloids/ghosts.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/potentials.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace narrows::colloids {

void fixed_range_error(double f) {
  std::ostringstream os;
  os << "colloid force component " << f << " is not finite or beyond the fixed-point range "
     << fixed::max_magnitude
     << " (a particle ran deep into a colloid within one MD step; allowed: a smaller MD "
        "step, i.e. more colloids.md_substeps, or weaker forces)";
  throw invariant_error(os.str());
}

void CellList::size_for(const mpcd::Box &box, double cut) {
  std::size_t n = 1;
  for (int k = 0; k < box.dim; ++k) {
    cells[k] = std::max(1, static_cast<int>(std::floor(box.length[k] / cut)));
    inv_cell[k] = cells[k] / box.length[k];
    n *= static_cast<std::size_t>(cells[k]);
  }
  head.assign(n, -1);
  filled.clear();
}

void FluidForces::clear(int dim) {
  for (const std::uint32_t i : touched) {
    flag[i] = 0;
    for (int k = 0; k < dim; ++k)
      value[static_cast<std::size_t>(i) * dim + k] = 0;
  }
  touched.clear();
}

namespace {

void build_fluid_cells(CellList &cl, const mpcd::Fluid &f, int dim) {
  const std::size_t n = f.size();
  cl.clear();
  cl.next.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t cell = 0;
    for (int k = dim - 1; k >= 0; --k) {
      const int ck =
          mpcd::clamped_cell(f.x[k][i], cl.inv_cell[k], cl.cells[k], "fluid particle", f.id[i], k);
      cell = cell * static_cast<std::size_t>(cl.cells[k]) + static_cast<std::size_t>(ck);
    }
    cl.push(cell, static_cast<std::int32_t>(i));
  }
}

} // namespace

ForceField::ForceField(const ForceParams &params, const mpcd::Box &box)
    : params_(params), box_(box), dim_(box.dim) {}

void ForceField::size_cells(double r_max) {
  // Fluid cells at least the largest WCA cut-off wide, colloid cells at least the largest
  // 48-24 cut-off, for the largest radius seen so far (cells wider than the cut-off serve
  // smaller colloids too; the radii are fixed, so this runs once).
  if (r_max <= cell_radius_)
    return;
  cell_radius_ = r_max;
  fluid_cells_.size_for(box_, repulsive_cutoff(6, r_max));
  colloid_cells_.size_for(box_, repulsive_cutoff(24, 2.0 * r_max));
}

template <int D, bool WallsY>
PotentialEnergy ForceField::compute(const mpcd::Fluid &f, const Colloids &c, ColloidGhosts *ghosts,
                                    MPI_Comm comm, bool want_energy) {
  const std::size_t n = f.size(), nc = c.size();
  const std::size_t owned = ghosts ? ghosts->owned() : nc;
  // Forces of the previous call are cleared where they were set; arrays grow with the fluid.
  fluid_.clear(D);
  fluid_.value.resize(n * D, 0);
  fluid_.flag.resize(n, 0);
  double r_max = 0.0;
  for (const double r : c.radius)
    r_max = std::max(r_max, r);
  size_cells(r_max);
  const double eps = params_.epsilon;
  PotentialEnergy energy;
  colloid_.assign(nc * D, 0);
  if (cell_radius_ > 0.0) // the list near_fluid.hpp uses too, also when this rank has no colloid
    build_fluid_cells(fluid_cells_, f, D);

  // Terms between fluid and colloids: this rank's fluid on its own and its ghost colloids; the
  // ghosts' shares go to their owners.
  if (nc > 0)
    energy.colloid_fluid = add_colloid_fluid_wca<D, WallsY>(fluid_cells_, f, c, box_, eps,
                                                            want_energy, fluid_, colloid_);
  if (ghosts)
    ghosts->reverse(colloid_, D);

  // Terms among colloids and of external fields, on the owned rows. Contact forces with
  // history would be added here.
  if (nc > 0)
    energy.colloid_colloid = add_colloid_colloid_4824<D, WallsY>(
        colloid_cells_, colloid_cell_, partners_, c, owned, box_, eps, want_energy, colloid_);
  if constexpr (WallsY)
    energy.wall = add_wall_lj<D>(c, owned, box_, eps, params_.sigma_wall, params_.wall_q, colloid_);
  add_gravity<D>(c, owned, params_.gravity, colloid_);
  if (want_energy && comm != MPI_COMM_NULL) { // each pair and wall term on one rank
    std::array<double, 3> mine{energy.colloid_fluid, energy.colloid_colloid, energy.wall}, sum{};
    MPI_Allreduce(mine.data(), sum.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
    energy = {sum[0], sum[1], sum[2]};
  }
  return energy;
}

PotentialEnergy ForceField::compute(const mpcd::Fluid &fluid, const Colloids &colloids,
                                    ColloidGhosts *ghosts, MPI_Comm comm, bool want_energy) {
  if (dim_ == 3)
    return box_.walls_y ? compute<3, true>(fluid, colloids, ghosts, comm, want_energy)
                        : compute<3, false>(fluid, colloids, ghosts, comm, want_energy);
  return box_.walls_y ? compute<2, true>(fluid, colloids, ghosts, comm, want_energy)
                      : compute<2, false>(fluid, colloids, ghosts, comm, want_energy);
}

} // namespace narrows::colloids
