// No-slip colloids: their motion over a step, the impulses they collect, the hand-over.
#include "narrows/engines/mpcd/coupling/no_slip.hpp"

#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/ownership.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/paths.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/coupling/near_fluid.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"
#include "narrows/parallel/message_clock.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

namespace narrows::coupling {

using namespace narrows::colloids;

namespace {

// Added to each colloid's path over a step when choosing ghost colloids (hard contacts change
// velocities within the step).
constexpr double path_allowance = 0.25;

} // namespace

void rotate(Colloids &c, std::size_t a, double dt) {
  // q <- exp(Omega dt / 2) q: the rotation by |Omega| dt about Omega (space frame), exact for an
  // angular velocity constant over dt; renormalised against the drift of round-off.
  const double w[3] = {c.omega[0][a], c.omega[1][a], c.omega[2][a]};
  const double rate = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (rate == 0.0)
    return;
  const double half = 0.5 * rate * dt, s = std::sin(half) / rate;
  const double d[4] = {std::cos(half), w[0] * s, w[1] * s, w[2] * s};
  const double q[4] = {c.q[0][a], c.q[1][a], c.q[2][a], c.q[3][a]};
  double r[4] = {d[0] * q[0] - d[1] * q[1] - d[2] * q[2] - d[3] * q[3],
                 d[0] * q[1] + d[1] * q[0] + d[2] * q[3] - d[3] * q[2],
                 d[0] * q[2] - d[1] * q[3] + d[2] * q[0] + d[3] * q[1],
                 d[0] * q[3] + d[1] * q[2] - d[2] * q[1] + d[3] * q[0]};
  const double norm = 1.0 / std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
  for (int k = 0; k < 4; ++k)
    c.q[k][a] = r[k] * norm;
}

NoSlipCoupling::NoSlipCoupling(const NoSlipParams &params, const mpcd::Box &box,
                               const parallel::Slabs &slabs)
    : params_(params), box_(box), dim_(box.dim), slabs_(slabs), ghosts_(slabs, box),
      migration_(slabs.comm()), contact_migration_(slabs.comm()) {
  dof_ = dim_ == 2 ? 3 : 6;
  stride_ = params_.implicit ? dof_ + dof_ * dof_ : dof_;
  history_.dim = dim_;
  if (params_.spring_contacts)
    springs_.emplace(params_.spring, box_);
}

Stages NoSlipCoupling::before_stream(const StageContext &at) {
  // The collision's v2_max is read when the stage runs: the last step's collision found it.
  return {{at.colloids_name,
           [this, &fluid = at.fluid, &colloids = at.colloids, &collision = at.collision](
               std::uint64_t) { move_colloids(fluid, colloids, collision.v2_max); }}};
}

Stages NoSlipCoupling::after_stream(const StageContext &at) {
  return {{"bounce-back of fluid that entered a colloid (U + Omega x r at the surface, halved "
           "intervals; impulses to the colloids)",
           [this, &fluid = at.fluid, &colloids = at.colloids, stream = at.stream](std::uint64_t) {
             bounced_ += bounce_back(fluid, colloids, stream).particles;
           }}};
}

Stages NoSlipCoupling::after_bin(const StageContext &at) {
  std::ostringstream density;
  density << params_.density;
  return {{"ghost particles in the cells cut by colloid surfaces (density " + density.str() +
               ", rigid-body velocity + Maxwell-Boltzmann; each colloid's in a cell as one group "
               "of sums)",
           [this, &grid = at.grid, &colloids = at.colloids](std::uint64_t step) {
             add_ghost_particles(grid, colloids, step);
           }}};
}

Stages NoSlipCoupling::within_collide(const StageContext &at) {
  return {{"ghost particles' momentum and angular momentum change to the colloids",
           [this, &grid = at.grid, &fluid = at.fluid, &colloids = at.colloids,
            &collision = at.collision](std::uint64_t) {
             take_back_ghost_particles(grid, collision, fluid, colloids);
             hand_over(colloids); // ghost colloids go; colloids that left the slab change owner
           }}};
}

const char *NoSlipCoupling::stage_name(int s) {
  static const char *const names[stage_count] = {"motion",      "contacts",    "lookup",
                                                 "bounce-back", "ghost sums",  "responses",
                                                 "solve",       "fluid shift", "hand-over"};
  return names[s];
}

void NoSlipCoupling::move_colloids(const mpcd::Fluid &fluid, Colloids &c, double fluid_v2_max) {
  const ScopedSeconds timed(seconds_);
  Stopwatch whole;
  const double dt = params_.dt;
  const std::size_t owned = c.size();
  for (std::size_t a = 0; a < owned; ++a) { // gravity: a kick of the whole step
    if (!params_.spring_contacts) // (springs: a force in each sub-step, balanced by contacts)
      for (int k = 0; k < dim_; ++k)
        c.v[k][a] += params_.gravity[k] * dt;
    rotate(c, a, dt);
  }
  // Each colloid's path this step: its speed, or with contacts up to twice the fastest speed
  // more (a collision can pass on the speed of the partner).
  const bool contacts = params_.hard_contacts || params_.spring_contacts;
  margin_.resize(owned);
  double fastest = 0.0;
  for (std::size_t a = 0; a < owned; ++a) {
    double v2 = 0.0;
    for (int k = 0; k < dim_; ++k)
      v2 += c.v[k][a] * c.v[k][a];
    margin_[a] = std::sqrt(v2);
    fastest = std::max(fastest, margin_[a]);
  }
  // The fluid's reach sizes the regions of other ranks (a pass over the fluid): not needed on
  // one rank, where every colloid is owned and nothing is copied.
  const double accel = std::sqrt(params_.fluid_accel[0] * params_.fluid_accel[0] +
                                 params_.fluid_accel[1] * params_.fluid_accel[1] +
                                 params_.fluid_accel[2] * params_.fluid_accel[2]) +
                       std::abs(params_.sine_amplitude);
  const double reach = ghosts_.active() ? fluid_reach(fluid, dt, accel, fluid_v2_max) : 0.0;
  // The step's one collective: the fastest colloid and the fluid's largest reach of all ranks,
  // and a stop signal any rank received (the run loop's poll then needs none of its own).
  const double signal = stop_signal_.received ? stop_signal_.received() : 0.0;
  double own[3] = {fastest, reach, signal};
  double all[3] = {own[0], own[1], own[2]};
  if (ghosts_.active()) {
    const ScopedSeconds talk(message_seconds_);
    const parallel::MessageTimer timed;
    MPI_Allreduce(own, all, 3, MPI_DOUBLE, MPI_MAX, slabs_.comm());
    if (stop_signal_.agreed)
      stop_signal_.agreed(static_cast<int>(all[2]));
  }
  const double v_max = all[0];
  const auto path = [&](double speed) {
    return contacts ? (speed + 2.0 * v_max) * dt + path_allowance
                    : speed * dt * (1.0 + 1e-12) + 1e-12;
  };
  for (std::size_t a = 0; a < owned; ++a)
    margin_[a] = path(margin_[a]);
  const double r_max = ghosts_.largest_radius(c);
  // The largest margin of all ranks: the path of the fastest colloid (path() is monotonic in
  // the speed, each of its operations correctly rounded: the same number as the largest of
  // the margins).
  const double m_max = path(v_max);
  // With contacts the region reaches four collision distances further, so that the ghosts an
  // owned colloid can meet in a chain of up to three contacts within the step are all here and
  // trusted (trusted_rows; a longer chain is refused).
  // With spring contacts each rank moves its ghosts itself through the sub-steps (no messages
  // between them): a ghost's motion is exact while every colloid it can touch is here and
  // exact. A colloid can touch those within one contact distance `contact` of its start (two
  // radii and two paths) within the step; a ghost within the region less one contact
  // distance has all of them, and the exact region shrinks by one contact distance at each of
  // the 1 + substeps force evaluations of a step. The region is widened by substeps + 2
  // contact distances, so the colloids within its unwidened extent plus one contact distance
  // end the step exact: those the fluid of this rank meets (lookup) and those the owned
  // colloids touch. (Beyond it the ghosts' copies may go wrong; they are dropped at the
  // hand-over, and check_paths below refuses one that strayed further than its path allows.)
  const double contact = 2.0 * r_max + 2.0 * m_max;
  double more = 0.0;
  if (params_.hard_contacts)
    more = 4.0 * contact;
  else if (springs_)
    more = (springs_->params().substeps + 2.0) * contact;
  {
    const ScopedSeconds talk(message_seconds_);
    ghosts_.add_for_step_agreed(c, margin_, m_max, all[1], more);
  }
  for (int k = 0; k < dim_; ++k)
    start_[k].assign(c.x[k].begin(), c.x[k].end());
  Stopwatch contact_watch;
  if (params_.hard_contacts) {
    ghosts_.trusted_rows(c, contact, trusted_);
    const HardSphereStats e = advance_hard_spheres(c, box_, dt, &trusted_);
    contacts_.pair_collisions += e.pair_collisions;
    contacts_.wall_collisions += e.wall_collisions;
    for (std::size_t a = 0; a < owned; ++a)
      if (!trusted_[a]) {
        std::ostringstream os;
        os << "colloid id " << c.id[a]
           << " took part in a chain of contacts reaching beyond the ghost colloids of this "
              "rank within one step (allowed: fewer ranks, or a smaller fluid.dt)";
        throw invariant_error(os.str());
      }
    const ScopedSeconds talk(message_seconds_);
    ghosts_.refresh_positions(c); // the owners' paths (a ghost may have missed a partner)
    ghosts_.refresh_motion(c);
  } else if (springs_) {    // every pair this rank holds, ghosts too (the ghost shell above)
    if (ghosts_.active()) { // the springs of the ghosts' contacts
      const ScopedSeconds talk(message_seconds_);
      ghosts_.copy_contacts(history_, c);
    }
    const std::size_t rows = c.size();
    const bool falling = params_.gravity != std::array<double, 3>{0.0, 0.0, 0.0};
    weight_.resize(rows * static_cast<std::size_t>(dim_));
    for (std::size_t a = 0; a < rows; ++a)
      for (int k = 0; k < dim_; ++k)
        weight_[a * static_cast<std::size_t>(dim_) + k] = c.mass[a] * params_.gravity[k];
    springs_->advance(c, rows, history_, dt, falling ? &weight_ : nullptr, owned);
    if (ghosts_.active()) {
      keep_contacts_of(history_, c, owned); // (the ghosts' copies go; their owners have them)
      check_paths(c, owned, rows, start_, margin_, box_, 0.0,
                  "its path allows, as a ghost copy moved through the spring sub-steps here (the "
                  "ghost shell was too thin for it: report it)");
      const ScopedSeconds talk(message_seconds_);
      ghosts_.drop_widening(c, margin_, start_); // (the shell's work is done)
    }
  } else {
    move_ballistic(c, c.size(), box_, dt); // owned and ghost rows alike: the same bits
  }
  const double contact_time = contact_watch.seconds();
  stage_seconds_[contact_forces] += contact_time;
  check_paths(c, owned, start_, margin_, box_, 0.0,
              "its speed and those of the others allowed (allowed: a smaller fluid.dt)");
  Stopwatch lookup_watch;
  lookup_.build(c, box_, slabs_.first_column(), slabs_.local_columns(),
                params_.hard_contacts ? ghosts_.extent() : ghosts_.base_extent());
  impulse_.assign(c.size() * static_cast<std::size_t>(stride_), 0);
  const double looked = lookup_watch.seconds();
  stage_seconds_[lookup] += looked;
  stage_seconds_[motion] += whole.seconds() - looked - contact_time;
}

void NoSlipCoupling::add_impulse(std::size_t a, const double *r, const double *dp,
                                 const double *more) {
  std::int64_t *s = &impulse_[a * static_cast<std::size_t>(stride_)];
  for (int k = 0; k < dim_; ++k)
    s[k] += fixed::from_double(dp[k]);
  const double zero[3] = {0.0, 0.0, 0.0};
  const double *m = more ? more : zero;
  if (dim_ == 2) {
    s[2] += fixed::from_double(r[0] * dp[1] - r[1] * dp[0] + m[0]);
  } else {
    s[3] += fixed::from_double(r[1] * dp[2] - r[2] * dp[1] + m[0]);
    s[4] += fixed::from_double(r[2] * dp[0] - r[0] * dp[2] + m[1]);
    s[5] += fixed::from_double(r[0] * dp[1] - r[1] * dp[0] + m[2]);
  }
}

void NoSlipCoupling::surface_map(const double *r, double f, double (&J)[3][6]) const {
  // dU + dOmega x r: 2D dof (Ux, Uy, Omega_z); 3D (Ux, Uy, Uz, Omega_x, Omega_y, Omega_z).
  for (auto &row : J)
    std::fill(std::begin(row), std::end(row), 0.0);
  for (int k = 0; k < dim_; ++k)
    J[k][k] = f;
  if (dim_ == 2) {
    J[0][2] = -f * r[1];
    J[1][2] = f * r[0];
  } else { // (W x r)_0 = W_1 r_2 - W_2 r_1, ...
    J[0][4] = f * r[2];
    J[0][5] = -f * r[1];
    J[1][3] = -f * r[2];
    J[1][5] = f * r[0];
    J[2][3] = f * r[1];
    J[2][4] = -f * r[0];
  }
}

void NoSlipCoupling::add_response(std::size_t a, const double (&J)[3][6], const double *lever) {
  // Rows: momentum J dX, then angular momentum lever x (J dX) about the centre.
  double G[6][6] = {};
  for (int k = 0; k < dim_; ++k)
    for (int j = 0; j < dof_; ++j)
      G[k][j] = J[k][j];
  for (int j = 0; j < dof_; ++j)
    if (dim_ == 2) {
      G[2][j] = lever[0] * J[1][j] - lever[1] * J[0][j];
    } else {
      G[3][j] = lever[1] * J[2][j] - lever[2] * J[1][j];
      G[4][j] = lever[2] * J[0][j] - lever[0] * J[2][j];
      G[5][j] = lever[0] * J[1][j] - lever[1] * J[0][j];
    }
  add_G(a, G);
}

void NoSlipCoupling::add_G(std::size_t a, const double (&G)[6][6]) {
  std::int64_t *s = &impulse_[a * static_cast<std::size_t>(stride_) + dof_];
  for (int i = 0; i < dof_; ++i)
    for (int j = 0; j < dof_; ++j)
      s[i * dof_ + j] += fixed::from_double(G[i][j]);
}

void NoSlipCoupling::apply_impulses(Colloids &c, bool refresh) {
  {
    const ScopedSeconds talk(message_seconds_);
    ghosts_.reverse(impulse_, stride_);
  }
  const std::size_t rows = c.size();
  if (params_.implicit) { // every row's U and Omega before, for dX/2 of the ghost rows
    before_.resize(rows * dof_);
    for (std::size_t a = 0; a < rows; ++a)
      for (int k = 0; k < dof_; ++k)
        before_[a * dof_ + k] = k < dim_ ? c.v[k][a] : c.omega[dim_ == 2 ? 2 : k - 3][a];
  }
  for (std::size_t a = 0; a < ghosts_.owned(); ++a) {
    const std::int64_t *s = &impulse_[a * static_cast<std::size_t>(stride_)];
    const double m = c.mass[a];
    const double inertia = moment_of_inertia(c, a);
    double dX[6];
    if (params_.implicit) { // (M + G/2) dX = dP
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> A(dof_, dof_);
      Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> b(dof_);
      for (int i = 0; i < dof_; ++i) {
        b[i] = fixed::to_double(s[i]);
        for (int j = 0; j < dof_; ++j)
          A(i, j) = 0.5 * fixed::to_double(s[dof_ + i * dof_ + j]) +
                    (i == j ? (i < dim_ ? m : inertia) : 0.0);
      }
      const auto x = A.partialPivLu().solve(b).eval();
      for (int i = 0; i < dof_; ++i)
        dX[i] = x[i];
    } else {
      for (int i = 0; i < dof_; ++i)
        dX[i] = fixed::to_double(s[i]) / (i < dim_ ? m : inertia);
    }
    for (int k = 0; k < dim_; ++k)
      c.v[k][a] += dX[k];
    if (dim_ == 2)
      c.omega[2][a] += dX[2];
    else
      for (int k = 0; k < 3; ++k)
        c.omega[k][a] += dX[3 + k];
  }
  std::fill(impulse_.begin(), impulse_.end(), 0);
  if (refresh || params_.implicit) {
    const ScopedSeconds talk(message_seconds_);
    ghosts_.refresh_motion(c);
  }
  if (params_.implicit) {
    half_.resize(rows * dof_);
    for (std::size_t a = 0; a < rows; ++a)
      for (int k = 0; k < dof_; ++k)
        half_[a * dof_ + k] = 0.5 * ((k < dim_ ? c.v[k][a] : c.omega[dim_ == 2 ? 2 : k - 3][a]) -
                                     before_[a * dof_ + k]);
  }
}

void NoSlipCoupling::hand_over(Colloids &c) {
  const ScopedSeconds timed(seconds_);
  const ScopedSeconds stage(stage_seconds_[hand_over_stage]);
  ghosts_.remove(c, &margin_);
  if (ghosts_.active()) {
    const ScopedSeconds talk(message_seconds_);
    // A colloid moved at most the largest margin this step: it goes at most that far (and a
    // column of grid shift) beyond the slab it was in.
    const double moved = ghosts_.largest_margin() + 2.0;
    migration_.set_neighbours(slabs_, moved, "colloid");
    if (springs_) { // each contact goes where its owner colloid goes
      contact_migration_.set_neighbours(slabs_, moved, "contact");
      migrate_contacts(history_, c, slabs_, contact_migration_);
    }
    migrate_colloids(c, slabs_, migration_);
  }
}

void NoSlipCoupling::set_slabs(const parallel::Slabs &slabs, Colloids &c) {
  const ScopedSeconds timed(seconds_);
  const ScopedSeconds stage(stage_seconds_[hand_over_stage]);
  slabs_ = slabs;
  // The ghosts' state lives for a step (nothing is kept between steps but the radii): made
  // again for the new slabs.
  std::destroy_at(&ghosts_);
  std::construct_at(&ghosts_, slabs_, box_);
  const ScopedSeconds talk(message_seconds_);
  // (to any rank: the old slabs' neighbours may not reach; the next hand-over sets them again)
  contact_migration_.clear_neighbours();
  migration_.clear_neighbours();
  if (springs_) // each contact goes where its owner colloid goes (before the colloids leave)
    migrate_contacts(history_, c, slabs_, contact_migration_);
  migrate_colloids(c, slabs_, migration_);
}

} // namespace narrows::coupling
