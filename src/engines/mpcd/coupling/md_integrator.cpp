// Velocity-Verlet sub-steps of the colloids and the fluid near them.
#include "narrows/engines/mpcd/coupling/md_integrator.hpp"

#include "narrows/colloids/ownership.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/paths.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/coupling/near_fluid.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <cmath>
#include <memory>
#include <sstream>

namespace narrows::coupling {

using namespace narrows::colloids;

namespace {

// Added to each colloid's path over a step when choosing the fluid particles of the sub-steps.
constexpr double path_allowance = 0.25;

} // namespace

MdIntegrator::MdIntegrator(const MdParams &params, const ForceParams &forces, const mpcd::Box &box,
                           const parallel::Slabs &slabs)
    : params_(params), box_(box), dim_(box.dim), slabs_(slabs), forces_(forces, box),
      ghosts_(slabs, box), migration_(slabs.comm()) {}

Stages MdIntegrator::before_stream(const StageContext &at) {
  return {{"MD: forces, ghost colloids, a copy of the fluid that may meet a colloid this step",
           [this, &fluid = at.fluid, &colloids = at.colloids](std::uint64_t) {
             take_near_fluid(fluid, colloids);
           }}};
}

Stages MdIntegrator::after_stream(const StageContext &at) {
  return {{at.colloids_name + "; fluid between kicks: " + at.stream_name,
           [this, &fluid = at.fluid, &colloids = at.colloids, stream = at.stream](std::uint64_t) {
             substeps(colloids, stream);
             put_back_near_fluid(fluid);
             check_paths(colloids);
             hand_over(colloids); // ghosts dropped; colloids that left the slab change owner
           }}};
}

void MdIntegrator::take_near_fluid(const mpcd::Fluid &fluid, Colloids &colloids) {
  // Forces depend on positions only, which the collision does not change: they are computed
  // afresh here rather than carried across the migration of the fluid.
  // Cells for the largest colloid anywhere: the fluid's cell list built here also serves the
  // choice of near fluid below, for ghosts that arrive only then.
  forces_.size_cells(ghosts_.largest_radius(colloids));
  ghosts_.add_for_forces(colloids);
  forces_.compute(fluid, colloids, &ghosts_, slabs_.comm());
  ghosts_.remove(colloids);
  const double dt = params_.tau * params_.substeps;
  const std::size_t nc = colloids.size();
  margin_.resize(nc);
  for (int k = 0; k < dim_; ++k)
    start_[k] = colloids.x[k];
  for (std::size_t a = 0; a < nc; ++a) {
    double v2 = 0.0, f2 = 0.0;
    for (int k = 0; k < dim_; ++k) {
      v2 += colloids.v[k][a] * colloids.v[k][a];
      const double f = fixed::to_double(forces_.colloid_force(a, k));
      f2 += f * f;
    }
    // Fluid kicks change the force within the step, so a fixed allowance is added to the path
    // the start values give (a thermal colloid moves ~0.01 per step of 0.1).
    margin_[a] = std::sqrt(v2) * dt + std::sqrt(f2) / colloids.mass[a] * dt * dt + path_allowance;
  }
  const double reach = fluid_reach(fluid, dt, params_.fluid_accel);
  ghosts_.add_for_step(colloids, margin_, reach);
  select_near_fluid(forces_.fluid_cells(), fluid, colloids, box_, margin_, dt, params_.fluid_accel,
                    reach, near_flag_, near_index_);
  const std::size_t m = near_index_.size();
  near_.dim = dim_;
  near_.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    const std::uint32_t i = near_index_[j];
    for (int k = 0; k < dim_; ++k) {
      near_.x[k][j] = fluid.x[k][i];
      near_.v[k][j] = fluid.v[k][i];
    }
    near_.id[j] = fluid.id[i];
  }
}

void MdIntegrator::kick(mpcd::Fluid &f, Colloids &c) const {
  // Half a step of the current forces: v += F tau / (2 m), fluid mass 1; owned colloids only.
  const double h = 0.5 * params_.tau;
  const auto &on_fluid = forces_.fluid_forces().value;
  for (const std::uint32_t i : forces_.fluid_forces().touched)
    for (int k = 0; k < dim_; ++k)
      f.v[k][i] += fixed::to_double(on_fluid[static_cast<std::size_t>(i) * dim_ + k]) * h;
  for (std::size_t a = 0; a < ghosts_.owned(); ++a) {
    const double s = h / c.mass[a];
    for (int k = 0; k < dim_; ++k)
      c.v[k][a] += fixed::to_double(forces_.colloid_force(a, k)) * s;
  }
}

void MdIntegrator::substeps(Colloids &colloids, const FluidStream &stream) {
  const double tau = params_.tau;
  const std::size_t owned = ghosts_.owned();
  const MPI_Comm comm = slabs_.comm();
  forces_.compute(near_, colloids, &ghosts_,
                  comm); // the same colloid forces: every pair is in near_
  for (int s = 0; s < params_.substeps; ++s) {
    kick(near_, colloids);
    stream(near_, tau);
    move_ballistic(colloids, owned, box_, tau);
    ghosts_.refresh_positions(colloids);
    forces_.compute(near_, colloids, &ghosts_, comm);
    kick(near_, colloids);
  }
}

void MdIntegrator::put_back_near_fluid(mpcd::Fluid &fluid) const {
  for (std::size_t j = 0; j < near_index_.size(); ++j) {
    const std::uint32_t i = near_index_[j];
    for (int k = 0; k < dim_; ++k) {
      fluid.x[k][i] = near_.x[k][j];
      fluid.v[k][i] = near_.v[k][j];
    }
  }
}

void MdIntegrator::check_paths(const Colloids &colloids) const {
  ghosts_.check_region(near_);
  colloids::check_paths(colloids, ghosts_.owned(), start_, margin_, box_, 1e-12,
                        "its velocity and force allowed (a sudden force: more "
                        "colloids.md_substeps or a smaller fluid.dt)");
}

void MdIntegrator::hand_over(Colloids &colloids) {
  ghosts_.remove(colloids, &margin_);
  if (ghosts_.active()) { // (a colloid moved at most the largest margin, and a grid shift)
    migration_.set_neighbours(slabs_, ghosts_.largest_margin() + 2.0, "colloid");
    migrate_colloids(colloids, slabs_, migration_);
  }
}

void MdIntegrator::set_slabs(const parallel::Slabs &slabs, Colloids &colloids) {
  slabs_ = slabs;
  std::destroy_at(&ghosts_); // (nothing of it lasts between steps but the radii)
  std::construct_at(&ghosts_, slabs_, box_);
  migration_.clear_neighbours(); // (any rank: the old slabs' neighbours may not reach)
  migrate_colloids(colloids, slabs_, migration_);
}

PotentialEnergy MdIntegrator::potential_energy(const mpcd::Fluid &fluid, Colloids &colloids) {
  ghosts_.add_for_forces(colloids);
  const PotentialEnergy e = forces_.compute(fluid, colloids, &ghosts_, slabs_.comm(), true);
  ghosts_.remove(colloids);
  return e;
}

} // namespace narrows::coupling
